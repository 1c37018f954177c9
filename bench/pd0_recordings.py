"""The DVL's PD0 decoder on recordings (docs/drivers.md, "DVL: Teledyne RDI PD0"):
each file through build/bin/auv-pd0-dump, the framer and decoder the driver
runs, with what it decoded, skipped and refused, and its speed (the whole
tool: its start and its JSON lines included).

    bench/pd0_recordings.py [DIR_OR_FILE ...] [--dolfyn]

Without arguments: the real instruments' shapes of python/sim/devices/pd0_shapes.py
(WinRiver II, waves packets, Ocean Surveyor, Sentinel V, ...). Given RDI's own
files (dolfyn's example data: RDI_withBT.000, winriver02.PD0, vmdas02_os.ENR,
sentinelv_b5.pd0, ...): every whole ensemble should decode, none be refused but
a last one cut by the end of the file. --dolfyn also reads each file with
dolfyn (a test dependency) and prints its ensemble count, which is one less
than ours where dolfyn leaves the last ensemble out.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DUMP = ROOT / "build" / "bin" / "auv-pd0-dump"
SUFFIXES = {".000", ".pd0", ".enx", ".enr", ".ens", ".sta", ".lta"}


def files(args: list[str]) -> list[Path]:
    out: list[Path] = []
    for a in args:
        p = Path(a)
        out += sorted(f for f in p.iterdir() if f.suffix.lower() in SUFFIXES) if p.is_dir() else [p]
    return out


def dolfyn_count(path: Path) -> str:
    import logging
    import warnings

    import numpy as np
    import scipy.integrate

    for name, value in (("NaN", np.nan), ("float_", np.float64), ("product", np.prod)):
        if not hasattr(np, name):
            setattr(np, name, value)
    if not hasattr(np, "RankWarning"):
        np.RankWarning = np.exceptions.RankWarning
    if not hasattr(scipy.integrate, "cumtrapz"):
        scipy.integrate.cumtrapz = scipy.integrate.cumulative_trapezoid
    warnings.simplefilter("ignore")
    logging.disable(logging.CRITICAL)
    import dolfyn

    try:
        return str(dolfyn.read(str(path), userdata=False).sizes["time"])
    except Exception as e:  # dolfyn's own limits (7F79 packets, Sentinel V): say so
        return f"fails ({type(e).__name__})"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("paths", nargs="*", help="PD0 files or folders of them (default: the shapes)")
    ap.add_argument("--dolfyn", action="store_true", help="also count dolfyn's ensembles")
    a = ap.parse_args()
    if not DUMP.exists():
        print(f"{DUMP} is not built: run `make build`", file=sys.stderr)
        return 2
    tmp = None
    paths = files(a.paths)
    if not a.paths:
        from sim.devices import pd0_shapes

        tmp = tempfile.TemporaryDirectory()
        pd0_shapes.main([tmp.name])
        paths = sorted(Path(tmp.name).iterdir())
    head = f"{'file':32} {'bytes':>9} {'ens':>6} {'waves':>6} {'garbage':>8} {'restart':>7} {'MB/s':>7}  refused"
    print(head + ("  dolfyn" if a.dolfyn else ""))
    bad = 0
    for path in paths:
        t0 = time.perf_counter()
        p = subprocess.run([str(DUMP), str(path)], capture_output=True, text=True)
        dt = time.perf_counter() - t0
        if p.returncode != 0:
            print(f"{path.name:32} auv-pd0-dump failed: {p.stderr.strip()}")
            bad += 1
            continue
        s = json.loads(p.stdout.splitlines()[-1])
        size = path.stat().st_size
        refused = ", ".join(f"{k}: {v}" for k, v in s["refused"].items()) or "-"
        bad += any(k != "truncated ensemble" for k in s["refused"])
        line = (
            f"{path.name:32} {size:>9} {s['ensembles']:>6} {s['waves_packets']:>6} {s['garbage_bytes']:>8} "
            f"{s['restarts']:>7} {size / dt / 1e6:>7.1f}  {refused}"
        )
        print(line + (f"  {dolfyn_count(path)}" if a.dolfyn else ""))
    if tmp:
        tmp.cleanup()
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())

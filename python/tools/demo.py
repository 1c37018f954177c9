"""`make demo`: the richest scenario that works today.

Today (foundation): a C process publishes a synthetic vehicle over LCM, the
real lcm-logger records it together with annotations that make the log
self-describing (the type definitions), and the project's log reader decodes
every event and writes CSV. Later issues replace this with the simulator,
the managers and the multi-vehicle survey.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))

import lcm  # noqa: E402

from auvlcm.url import check_local, default_url  # noqa: E402


def annotate(lc: lcm.LCM) -> int:
    from auv import log_annotation_t
    count = 0
    for path in sorted((ROOT / "lcmtypes").glob("*.lcm")):
        note = log_annotation_t()
        note.utime, note.source, note.kind = 0, "demo", log_annotation_t.KIND_LCMTYPE
        note.name, note.text = path.name, path.read_text()
        lc.publish("SIM.ANNOTATION", note.encode())
        count += 1
    return count


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", type=Path, default=ROOT / "build" / "demo")
    parser.add_argument("--url", default=default_url())
    parser.add_argument("--seconds", type=float, default=4.0)
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    args = parser.parse_args()
    url = check_local(args.url)
    args.out.mkdir(parents=True, exist_ok=True)
    log_path = args.out / "foundation.lcmlog"
    logger_bin = Path(lcm.LCM_BIN_DIR).resolve() / "lcm-logger"

    print(f"demo: recording {url} to {log_path}")
    # The real binary in its own process group, so nothing is ever orphaned.
    logger = subprocess.Popen([str(logger_bin), f"--lcm-url={url}", "--quiet", "-f", str(log_path)],
                              start_new_session=True)
    try:
        time.sleep(0.5)
        lc = lcm.LCM(url)
        n_notes = annotate(lc)
        rate = 50
        pub = subprocess.run([str(args.build / "bin" / "auv-lcm-probe"), "publish-track", "--url", url,
                              "--vehicle", "AUV1", "--count", str(int(args.seconds * rate)),
                              "--rate", str(rate)], timeout=args.seconds + 30)
        if pub.returncode != 0:
            print("demo: publisher failed", file=sys.stderr)
            return 1
        time.sleep(0.5)
    finally:
        os.killpg(logger.pid, signal.SIGINT)
        logger.wait(10)

    tool = [sys.executable, str(ROOT / "python" / "tools" / "lcmlog.py")]
    rc = subprocess.call(tool + ["summary", str(log_path)])
    csv_path = args.out / "AUV1.NAV.csv"
    rc |= subprocess.call(tool + ["csv", str(log_path), "AUV1.NAV", str(csv_path)])
    print(f"\ndemo: {n_notes} type definitions annotated into the log")
    print(f"demo results: log {log_path}\n              csv {csv_path}")
    print("replay it for lcm-spy: make spy  (in one terminal), then\n"
          f"  {logger_bin.parent}/lcm-logplayer {log_path}")
    return rc


if __name__ == "__main__":
    sys.exit(main())

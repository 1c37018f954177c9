"""Fuzz the configuration readers: the simulator config (sim.config) and the
scenario (tools.scenario.scenario_file), by seeded mutation of the shipped files.

Every input must end in success or a ConfigError whose lines are
`file:line:col: ...` (or `file: ...`); any other exception, or one input
taking longer than --max-input-s, is a failure: the input is saved as
config-crash-N.yaml in the working folder and the exit status is 1.

    config_fuzz.py [--runs N | --seconds S] [--seed K]       (make fuzz; tests run a short one)
"""

from __future__ import annotations

import argparse
import random
import sys
import tempfile
import time
import traceback
from pathlib import Path

from confcheck import ConfigError

ROOT = Path(__file__).resolve().parents[2]

TOKENS = [
    b"[",
    b"]",
    b"{",
    b"}",
    b": ",
    b"\n",
    b"- ",
    b"&a ",
    b"*a",
    b"<<: *a",
    b"!!python/object:os.system ",
    b"!!binary ",
    b"\xff",
    b"\xc3",
    b"\x00",
    b"\t",
    b"1e400",
    b"-1",
    b".nan",
    b".inf",
    b"SIM",
    b"MODEM",
    b"'",
    b'"',
    b"#",
    b"?",
    b"%YAML 1.1\n",
    b"---\n",
    b"~",
    b"yes",
    b"0x7fffffff",
    b"99999999999999999999",
    b"[" * 40,
    b"{a: " * 40,
    b"\n  " * 3,
    b"\xe2\x80\xa8",
    b"|\n  a\n  b\n",
]


def seeds() -> list[tuple[str, bytes]]:
    out = [("sim", p.read_bytes()) for p in sorted((ROOT / "missions" / "sim").glob("*.yaml"))]
    out += [
        ("scenario", p.read_bytes())
        for p in sorted((ROOT / "missions" / "scenarios").rglob("*.yaml"))
        if b"vehicles:" in p.read_bytes()
    ]
    out += [("scenario", (ROOT / "tests" / "tools" / "scenarios" / "two_vehicles.yaml").read_bytes())]
    out += [
        ("set", s)
        for s in (
            b"sensors.gps.noise=2.5",
            b"vehicle.id=AUV7",
            b"initial={depth_m: 3, north_m: 1}",
            b"simulation.clock=lockstep",
            b"environment.current=[{depth_m: 0, north_mps: 0.1, east_mps: 0, down_mps: 0}]",
        )
    ]
    return out


def mutate(data: bytes, rng: random.Random) -> bytes:
    b = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        op = rng.randrange(6)
        at = rng.randrange(len(b) + 1)
        if op == 0 and b:
            b[min(at, len(b) - 1)] = rng.randrange(256)
        elif op == 1:
            b[at:at] = rng.choice(TOKENS)
        elif op == 2:
            del b[at : at + rng.randint(1, 40)]
        elif op == 3:
            lines = bytes(b).split(b"\n")
            i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
            b = bytearray(b"\n".join(lines))
        elif op == 4:
            lines = bytes(b).split(b"\n")
            i = rng.randrange(len(lines))
            lines.insert(i, lines[rng.randrange(len(lines))])
            b = bytearray(b"\n".join(lines))
        else:
            b = b[:at]
    return bytes(b)


def check_one(kind: str, data: bytes, folder: Path) -> None:
    """Raise AssertionError unless the reader ends cleanly."""
    path = folder / f"input_{kind}.yaml"
    path.write_bytes(data)
    try:
        if kind == "set":  # a auv-survey-log --set override: an argv string (undecodable bytes escaped)
            from sim.config import loads
            from tools.nav.survey_log import DEFAULT_CONFIG, apply_overrides

            item = data.decode("utf-8", errors="surrogateescape")
            path = Path(f"--set {item.partition('=')[0]}")
            text = apply_overrides(DEFAULT_CONFIG.read_text(), [item], DEFAULT_CONFIG)
            loads(text, path := folder / "merged.yaml")
        elif kind == "sim":
            from sim.config import load

            load(path)
        else:
            from tools.scenario.scenario_file import load_scenario

            load_scenario(path)
    except ConfigError as exc:
        assert exc.errors, "ConfigError without errors"
        for line in exc.errors:
            assert line.startswith(str(path)) or kind == "set", f"error without the file name: {line!r}"
    except ValueError as exc:  # survey_log's own "--set ...: expected key.path=value"
        assert kind == "set" and str(exc).startswith("--set "), repr(exc)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=0)
    ap.add_argument("--seconds", type=float, default=0.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--max-input-s", type=float, default=10.0)
    args = ap.parse_args(argv)
    if not args.runs and not args.seconds:
        args.runs = 500
    rng = random.Random(args.seed)
    corpus = seeds()
    start, n, crashes = time.monotonic(), 0, 0
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        while (args.runs and n < args.runs) or (args.seconds and time.monotonic() - start < args.seconds):
            kind, base = rng.choice(corpus)
            data = mutate(base, rng)
            t0 = time.monotonic()
            try:
                check_one(kind, data, folder)
                slow = time.monotonic() - t0 > args.max_input_s
                if slow:
                    raise AssertionError(f"took {time.monotonic() - t0:.1f} s")
            except BaseException as exc:  # noqa: BLE001 - anything else is the finding
                if isinstance(exc, KeyboardInterrupt):
                    raise
                crashes += 1
                out = Path.cwd() / f"config-crash-{crashes}.yaml"
                out.write_bytes(data)
                print(f"config_fuzz: {kind} input {n}: {type(exc).__name__}: {exc} (saved {out})")
                traceback.print_exc(limit=4)
            n += 1
    print(f"config_fuzz: {n} inputs (seed {args.seed}), " + ("no crash" if not crashes else f"{crashes} failure(s)"))
    return 1 if crashes else 0


if __name__ == "__main__":
    sys.exit(main())

"""Cost of command authentication per message (docs/security.md, "What it costs").

C (the managers' verifier, auv-auth-probe bench): decoding a mission_command_t
alone, the unsigned baseline, against decoding and verifying it (re-encoding
with mac_len 0, HMAC-SHA-256 with libcrypto, the counter checks). Python
(auvlcm.auth, as auvctl, the console and the agents use it): encode against
sign-and-encode, decode against decode-and-verify. For a small command (a
pause) and a plan load (64 KiB of plan text). Prints ns per message and the
ratio to the baseline."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from auv import mission_command_t
from auvlcm import auth

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("AUV_BUILD", ROOT / "build"))
if not BUILD.is_absolute():
    BUILD = ROOT / BUILD
KEY = auth.Key("bench", bytes(range(32)))
RING = auth.KeyRing((KEY,))


def message(plan_bytes: int) -> mission_command_t:
    m = mission_command_t()
    m.utime, m.vehicle, m.seq, m.reason = 1, "AUV1", 1, "bench"
    if plan_bytes:
        m.command, m.plan_name, m.plan_text = m.CMD_LOAD_PLAN, "p.chasm", "x" * plan_bytes
    else:
        m.command = m.CMD_PAUSE
    return m


def per_call_ns(fn, n: int) -> float:
    t0 = time.perf_counter_ns()
    for _ in range(n):
        fn()
    return (time.perf_counter_ns() - t0) / n


def python_figures(m: mission_command_t, n: int) -> tuple[float, float, float, float]:
    enc = per_call_ns(m.encode, n)
    sign = per_call_ns(lambda: auth.sign(m, RING, "bench").encode(), n)
    data = m.encode()
    dec = per_call_ns(lambda: mission_command_t.decode(data), n)

    def verify() -> None:
        v = auth.Verifier(RING)
        v.verify(mission_command_t.decode(data), now_us=m.auth.counter)

    ver = per_call_ns(verify, n)
    return enc, sign, dec, ver


def main() -> int:
    probe = BUILD / "bin" / "auv-auth-probe"
    if not probe.exists():
        print(f"{probe} is not built: run `make build`", file=sys.stderr)
        return 1
    print(f"{'message':<22} {'bytes':>7} {'side':<7} {'baseline ns':>12} {'with auth ns':>13} {'ratio':>6}")
    with tempfile.TemporaryDirectory() as tmp:
        keys = Path(tmp) / "k.key"
        keys.write_text(f"{KEY.id} {KEY.secret.hex()}\n")
        keys.chmod(0o600)
        for name, size, n in (("pause", 0, 20000), ("load plan 64 KiB", 65536, 2000)):
            m = auth.sign(message(size), RING, "bench")
            f = Path(tmp) / "m.bin"
            f.write_bytes(m.encode())
            run = subprocess.run([str(probe), "bench", str(keys), str(f), str(n)], capture_output=True, text=True)
            if run.returncode != 0:
                print(run.stdout + run.stderr, file=sys.stderr)
                return 1
            fields = run.stdout.split()
            c_dec, c_ver = float(fields[3]), float(fields[5])
            print(f"{name:<22} {len(m.encode()):>7} {'C recv':<7} {c_dec:>12.0f} {c_ver:>13.0f} {c_ver / c_dec:>6.1f}")
            enc, sign, dec, ver = python_figures(m, n // 4)
            print(f"{'':<22} {'':>7} {'Py send':<7} {enc:>12.0f} {sign:>13.0f} {sign / enc:>6.1f}")
            print(f"{'':<22} {'':>7} {'Py recv':<7} {dec:>12.0f} {ver:>13.0f} {ver / dec:>6.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Traffic per vehicle: messages and bytes per second of sim time, by channel
class, measured from a run's log; and what links of given capacity carry
(docs/scaling.md).

Runs the MCM demo scenario (3 vehicles, PILOT + NAVIGATOR + auv-nav each,
sidescan, the launcher's clock) for --limit sim seconds in fast time through
auv-launch, or reads an existing --log. Rates are per second of sim time, so a
fast-time run measures what a real-time one sends. Wire size of a message:
Ethernet framing 38 + IPv4 20 + UDP 8 + LCM short header 8 + channel name + 1
+ payload (one datagram per message up to 64 KB; larger ones fragment).

Run: tests/isolated_net.sh .venv/bin/python bench/traffic_bench.py [--limit 240] [--log LOG]
Prints figures, asserts nothing.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
from collections import defaultdict
from pathlib import Path

from auvlcm.log import read_events

ROOT = Path(__file__).resolve().parents[1]

SCENARIO = ROOT / "missions" / "scenarios" / "mcm_demo" / "mcm_demo.yaml"
FRAMING = 38 + 20 + 8 + 8 + 1  # bytes on the wire besides channel name and payload
CLASSES = [  # (class, channel regex), first match wins
    ("sensors", r"^[A-Z0-9]+\.(AHRS|DEPTH|DVL|ALTIMETER|GPS|LBL|NAV_INS)$"),
    ("navigation", r"^[A-Z0-9]+\.(NAV|NAV_STATUS)$"),
    ("control", r"^[A-Z0-9]+\.(ACTUATORS|ACTUATOR_STATE|SETPOINT)$"),
    ("chasm status", r"^[A-Z0-9]+\.CHASM\."),
    ("truth (evaluation)", r"^[A-Z0-9]+\.TRUTH$"),
    ("sonar contacts", r"^[A-Z0-9]+\.CONTACTS$"),
    ("modem/peers", r"^([A-Z0-9]+\.(MODEM_|PEER)|SIM\.ACOUSTIC)"),
    ("health", r"HEALTH$"),
    ("world clock/env (SIM.*)", r"^SIM\.(CLOCK|ENV|LOCKSTEP|TARGETS)"),
    ("annotations", r"^SIM\.ANNOTATION$"),
]


def classify(channel: str) -> str:
    return next((c for c, rx in CLASSES if re.search(rx, channel)), "other")


def run_scenario(limit: float, out: Path) -> Path:
    text = SCENARIO.read_text()
    base = SCENARIO.parent
    text = re.sub(
        r"(config|plan|bind|survey): (\S+)",
        lambda m: f"{m[1]}: {(base / m[2]).resolve()}" if not m[2].startswith("/") else m[0],
        text,
    )
    text = re.sub(r"limit: \d+(\.\d*)?", f"limit: {limit:g}", text, count=1)
    sc = out / "traffic.yaml"
    sc.write_text(text)
    subprocess.run([sys.executable, "-m", "tools.launch", str(sc), "--out", str(out), "--progress", "0"], check=False)
    return out / "run.lcmlog"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--log", type=Path)
    ap.add_argument("--limit", type=float, default=240.0, help="sim seconds to run (default 240)")
    ap.add_argument("--wan-mbps", type=float, action="append", default=[], help="WAN links to size (Mbit/s)")
    args = ap.parse_args()
    log = args.log or run_scenario(args.limit, Path(tempfile.mkdtemp(prefix="traffic-")))
    count, nbytes, wire = defaultdict(int), defaultdict(int), defaultdict(int)
    vehicles, t0, t1 = set(), None, None
    for ev in read_events(log):
        if ev.msg is None:
            continue
        m = re.match(r"^([A-Z][A-Z0-9]{0,15})\.", ev.channel)
        if m and m[1] != "SIM":
            vehicles.add(m[1])
        u = getattr(ev.msg, "utime", 0)
        if ev.channel == "SIM.CLOCK":
            t0 = u if t0 is None else min(t0, u)
            t1 = u if t1 is None else max(t1, u)
        c, size = classify(ev.channel), len(ev.msg.encode())  # the same bytes as sent
        count[c] += 1
        nbytes[c] += size
        wire[c] += size + len(ev.channel) + FRAMING
    span = (t1 - t0) / 1e6 if t0 is not None and t1 > t0 else float("nan")
    nv = max(len(vehicles), 1)
    print(f"log {log}: {nv} vehicles ({', '.join(sorted(vehicles))}), {span:.1f} s of sim time")
    print(f"{'class':26} {'msg/s/veh':>10} {'payload B/s/veh':>16} {'wire B/s/veh':>13} {'avg payload B':>14}")
    tot_m = tot_w = 0.0
    for c in [c for c, _ in CLASSES] + ["other"]:
        if not count[c]:
            continue
        per = 1.0 / (span * nv)
        tot_m += count[c] * per
        tot_w += wire[c] * per
        print(
            f"{c:26} {count[c] * per:10.1f} {nbytes[c] * per:16.0f} {wire[c] * per:13.0f} {nbytes[c] / count[c]:14.0f}"
        )
    print(f"{'total':26} {tot_m:10.1f} {'':16} {tot_w:13.0f}")
    print(f"per vehicle at 1x real time: {tot_m:.0f} msg/s, {tot_w * 8 / 1e6:.3f} Mbit/s on the wire")
    for name, mbps in [("1 GbE LAN (70 % usable)", 700.0)] + [
        (f"WAN {w:g} Mbit/s (70 %)", 0.7 * w) for w in (args.wan_mbps or [10.0, 2.0])
    ]:
        cap = mbps * 1e6 / 8 / tot_w
        print(
            f"{name:28} carries {cap:8.0f} vehicle-seconds per second (e.g. {cap:.0f} vehicles at 1x, "
            f"{cap / 10:.0f} at 10x)"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())

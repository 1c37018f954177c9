"""Multicast fan-out cost: what every LCM process pays for traffic it does
not want (docs/scaling.md).

On udpm every socket joined to the group receives every datagram of the
world; liblcm drops the channels nobody subscribed to only after the kernel
has delivered them. A publisher sends 200-byte messages on channel NOISE at a
fixed rate for a few seconds; receivers subscribe to (a) another channel
only, (b) NOISE with an empty Python handler. Their CPU time per message
received (from /proc) is the per-message fan-out cost; with R messages/s in
the world, each process spends R x that per second.
Run: tests/isolated_net.sh .venv/bin/python bench/fanout_bench.py
Prints figures, asserts nothing.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time

URL = "udpm://239.255.76.67:7931?ttl=0&recv_buf_size=8388608"
RECEIVER = r"""
import sys, time, lcm
lc = lcm.LCM(sys.argv[1]); n = [0]
lc.subscribe(sys.argv[2], lambda c, d: n.__setitem__(0, n[0] + 1)).set_queue_capacity(100000)
end = time.monotonic() + float(sys.argv[3])
while time.monotonic() < end:
    lc.handle_timeout(50)
import os
ts = os.times()
print(n[0], ts.user + ts.system, flush=True)
"""


def cpu_idle_receiver(channel: str, rate: int, seconds: float) -> tuple[int, float, int]:
    rx = subprocess.Popen(
        [sys.executable, "-c", RECEIVER, URL, channel, str(seconds + 2.0)], stdout=subprocess.PIPE, text=True
    )
    time.sleep(1.0)
    import lcm

    lc = lcm.LCM(URL)
    payload = bytes(200)
    sent, t0 = 0, time.monotonic()
    while time.monotonic() - t0 < seconds:
        due = int((time.monotonic() - t0) * rate)
        while sent < due:
            lc.publish("NOISE", payload)
            sent += 1
        time.sleep(0.001)
    out = rx.communicate(timeout=30)[0].split()
    return int(out[0]), float(out[1]), sent


def main() -> int:
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    print(f"fanout_bench ({os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start)")
    base_n, base_cpu, _ = cpu_idle_receiver("QUIET", 1, 4.0)  # startup and idle polling
    for rate in (2000, 8000):
        for channel, what in (("OTHER", "not subscribed"), ("NOISE", "subscribed, empty handler")):
            n, cpu, sent = cpu_idle_receiver(channel, rate, 4.0)
            per = (cpu - base_cpu) / sent * 1e6
            print(
                f"  {rate:5d} msg/s of 200 B, receiver {what:26}: {per:5.1f} us CPU per message in the world "
                f"({100 * (cpu - base_cpu) / 4.0:4.1f} % of a core; handled {n}/{sent})"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())

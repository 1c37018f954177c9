"""Modem and relay benchmark: prints figures, asserts nothing.

  1. the modem receiver's cost per physics step with frames in flight
     (in-process, no LCM): what a busy acoustic channel adds to a simulator
  2. the link-impairment relay over LCM (ttl=0): messages per second it
     forwards, and the latency it adds (p50, p99) with no impairment and with
     2 ms +- 1 ms delay, measured publisher -> relay -> subscriber
Run: tests/isolated_net.sh .venv/bin/python bench/modem_bench.py
"""

from __future__ import annotations

import argparse
import statistics
import struct
import subprocess
import sys
import time
from pathlib import Path

from auv import acoustic_frame_t, modem_status_t
from sim.environment import Environment, EnvParams
from sim.modem.config import ModemConfig
from sim.modem.receiver import Receiver

ROOT = Path(__file__).resolve().parents[1]

URL_A = "udpm://239.255.76.67:7791?ttl=0"
URL_B = "udpm://239.255.76.67:7792?ttl=0"


def receiver_cost(in_flight: int, steps: int = 2000) -> float:
    """Microseconds per Receiver.step with in_flight frames that never arrive."""
    rx = Receiver(ModemConfig(), "AUV2", 1, Environment(EnvParams()), modem_status_t())
    for seq in range(in_flight):
        f = acoustic_frame_t()
        f.utime, f.src_vehicle, f.seq, f.tx_north_m = 0, "AUV1", seq, 1e9  # far away
        rx.hear(f)
    t0 = time.perf_counter()
    for k in range(steps):
        rx.step(k * 0.02, (0.0, 0.0, 10.0))
    return (time.perf_counter() - t0) / steps * 1e6


def relay_run(extra: list[str], n: int, pace_s: float) -> tuple[float, int, float, float]:
    """(messages/s through the relay, messages received, p50 and p99 latency in ms)."""
    import lcm

    relay = subprocess.Popen(
        [sys.executable, "-m", "tools.bridges.lcm_relay", "--in", URL_A, "--out", URL_B, "--channel", "BENCH", *extra],
        stdout=subprocess.PIPE,
        text=True,
    )
    relay.stdout.readline()  # "running"
    a, b = lcm.LCM(URL_A), lcm.LCM(URL_B)
    lat: list[float] = []
    last = [0.0]

    def on_msg(_ch: str, d: bytes) -> None:
        last[0] = time.monotonic()
        lat.append(last[0] - struct.unpack(">d", d[:8])[0])

    b.subscribe("BENCH", on_msg).set_queue_capacity(100_000)
    t0 = time.monotonic()
    for _ in range(n):
        a.publish("BENCH", struct.pack(">d", time.monotonic()) + bytes(100))
        b.handle_timeout(0)
        if pace_s:
            time.sleep(pace_s)
    deadline = time.monotonic() + 5.0
    while len(lat) < n and time.monotonic() < deadline:
        b.handle_timeout(20)
    elapsed = last[0] - t0  # to the last arrival
    relay.terminate()
    relay.wait()
    lat_ms = sorted(x * 1e3 for x in lat)
    if not lat_ms:
        return 0.0, 0, float("nan"), float("nan")
    return (len(lat_ms) / elapsed, len(lat_ms), statistics.median(lat_ms), lat_ms[int(0.99 * (len(lat_ms) - 1))])


def main() -> None:
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    print("modem receiver, per physics step (in-process):")
    for k in (0, 10, 100):
        print(f"  {k:4d} frames in flight   {receiver_cost(k):8.1f} us/step")
    print("lcm_relay, 108-byte messages; latency = publisher -> relay -> subscriber:")
    impaired = ["--delay-ms", "2", "--jitter-ms", "1", "--loss", "0.05"]
    try:
        for label, extra, n, pace in (
            ("1000 at 1 kHz, no impairment", [], 1000, 0.001),
            ("1000 at 1 kHz, 2+-1 ms, 5 % loss", impaired, 1000, 0.001),
            ("3000 back to back", [], 3000, 0.0),
        ):
            rate, got, p50, p99 = relay_run(extra, n, pace)
            print(
                f"  {label:34s} {got:5d}/{n} through, {rate:6.0f} msg/s, latency p50 {p50:7.2f} ms, p99 {p99:7.2f} ms"
            )
    except OSError as exc:
        print(f"  skipped ({exc}); run under tests/isolated_net.sh")


if __name__ == "__main__":
    main()

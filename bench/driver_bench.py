"""What each device driver costs (docs/drivers.md, "Cost"), per driver of c/drivers/:

1. bytes per second parsed: the device's bytes written into a pseudo-terminal as
   fast as the driver takes them, per second of the driver's own CPU (LCM
   publishing included). auv-servo takes its input over LCM: actuators_t
   published as fast as possible. auv-depth is polled (it says nothing unasked):
   its sensor's answers go through auv-driver-replay from a recorded raw log.
2. CPU per second of device data: the device at its real rate for a while (each
   device's rate is in the table), answered where the driver asks (the depth
   sensor's polls, the Maestro's Get Errors, the modem's dialogue); the driver's
   CPU over the wall time, as a fraction of one core. Goal: well under 1 %.

The device's bytes are the simulator's own emulators' (python/sim/devices/*.py),
fed the simulator's sensor models (bench/driver_feeds.py). The CPU is the
driver process's own (/proc/PID/schedstat, nanoseconds).
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import lcm
from driver_feeds import VEHICLE, Feed, feeds
from driver_pty import BUILD, URL, Driver, drops

from auv import raw_bytes_t
from auvlcm import programs

CHUNK = 4096  # bytes per write of the as-fast-as-possible runs


class Row:
    def __init__(self, feed: Feed) -> None:
        self.feed = feed
        self.max_bps = self.max_fps = self.line_bps = self.cpu_pct = float("nan")
        self.how = "pty"


def fast_pty(d: Driver, row: Row, n_bytes: int) -> int:
    """Bursts written as fast as the driver reads them; returns the ticks used."""
    feed, chunks, buf, size, n = d.feed, [], bytearray(), 0, 0
    while size < n_bytes:  # writes of whole bursts: the device's answers go between them
        buf += feed.fast_burst(n)
        n += 1
        if len(buf) >= CHUNK or size + len(buf) >= n_bytes:
            chunks.append(bytes(buf))
            size += len(buf)
            buf.clear()
    s0 = d.wait(lambda s: s.port_open, 10)
    assert s0 is not None, f"{feed.label}: the port never opened"
    c0 = d.cpu()
    for chunk in chunks:
        d.write(chunk)
        d.service()
    # the driver's own counts (its 1 Hz status): a Python subscriber would lose messages at this rate
    s = d.wait(lambda s: s.bytes_read >= d.written, 120)
    cpu = d.cpu() - c0
    assert s is not None, f"{feed.label}: {d.written} bytes written, the driver read {d.status[-1].bytes_read}"
    row.max_bps, row.max_fps = size / cpu, (s.frames_decoded - s0.frames_decoded) / cpu
    print(
        f"{feed.label}: {size} bytes as fast as fed, {s.frames_decoded - s0.frames_decoded} frames, "
        f"{s.messages_published - s0.messages_published} published, {drops(s) - drops(s0)} dropped, {cpu:.2f} s CPU"
    )
    return n


def fast_lcm(d: Driver, row: Row, n: int) -> None:
    """Commands published over LCM as fast as possible: applied or refused, per CPU second."""
    s0 = d.wait(lambda s: s.port_open, 10)
    assert s0 is not None, f"{d.feed.label}: the port never opened"
    c0, size = d.cpu(), 0
    for i in range(n):
        suffix, data = d.feed.command(i) or ("", b"")
        d.lc.publish(f"{VEHICLE}.{suffix}", data)
        size = len(data)
        if i % 50 == 0:
            d.service()
    # until the counts stop growing (a datagram the kernel dropped never comes; the
    # Maestro's answer to the 1 Hz Get Errors is a frame too)
    handled = -10
    while (now := (s := d.next_status()).frames_decoded + drops(s)) > handled + 2:
        handled = now
    cpu, s = d.cpu() - c0, d.status[-1]
    frames = s.frames_decoded - s0.frames_decoded
    row.max_bps, row.max_fps, row.how = frames * size / cpu, frames / cpu, "LCM"
    print(
        f"{d.feed.label}: {n} actuators_t published as fast as possible, {frames} applied, "
        f"{drops(s) - drops(s0)} refused, {s.bytes_written - s0.bytes_written} bytes written, {cpu:.2f} s CPU"
    )


def fast_replay(feed: Feed, row: Row, tmp: Path, n_bytes: int) -> None:
    """A polled sensor's answers, recorded as the driver reads them, through auv-driver-replay."""
    answers, polls = feed.recorded(n_bytes)
    log_path = tmp / f"{feed.program}.lcmlog"
    log = lcm.EventLog(str(log_path), "w")
    for k in range(0, len(answers), CHUNK):
        m = raw_bytes_t()
        m.utime, m.vehicle, m.device = 1_700_000_000_000_000 + k, VEHICLE, feed.device
        m.direction, m.offset, m.data = raw_bytes_t.DIR_RX, k, answers[k : k + CHUNK]
        m.n_bytes = len(m.data)
        log.write_event(m.utime, f"{VEHICLE}.RAW.{feed.device}", m.encode())
    log.close()
    cmd = programs.driver_replay(BUILD, log=log_path, vehicle=VEHICLE, device=feed.device)
    with open(tmp / "replay.stderr", "w") as err:
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
    _, status, usage = os.wait4(proc.pid, 0)  # its CPU time, from the kernel's accounting
    summary = (tmp / "replay.stderr").read_text().strip().splitlines()[-1:]
    rc = os.waitstatus_to_exitcode(status)
    assert rc == 0, f"auv-driver-replay exited {rc}: {summary}"
    cpu = usage.ru_utime + usage.ru_stime
    row.max_bps, row.max_fps, row.how = len(answers) / cpu, polls / cpu, "replay"
    print(f"{feed.label}: {len(answers)} bytes of {polls} answers through auv-driver-replay, {cpu:.2f} s CPU")
    print(f"  replay: {' '.join(summary)}")


def at_rate(d: Driver, row: Row, i0: int, seconds: float) -> None:
    """The device at its real rate for `seconds`, after a second of it as a warm-up
    (the silence after a fast run, the driver's first answers): the driver's CPU
    over the wall time."""
    feed = d.feed
    assert d.wait(lambda s: s.port_open, 10) is not None, f"{feed.label}: the port never opened"
    warm = math.ceil(feed.rate_hz) if feed.rate_hz >= 1 else 0
    n = max(1, round(seconds * feed.rate_hz))
    t_start, k, end = time.monotonic(), 0, -1

    def done() -> bool:  # after the run, the device goes on until the next status
        return end >= 0 and len(d.status) > end

    while not done():
        due = t_start + k / feed.rate_hz
        while (left := due - time.monotonic()) > 0 and not done():
            d.service(min(left, 0.05))
        if k == warm:
            s0, w0, h0, c0, t0 = d.status[-1], d.written, d.heard, d.cpu(), time.monotonic()
        if k == warm + n:
            wall, cpu, end = time.monotonic() - t0, d.cpu() - c0, len(d.status)
            row.cpu_pct, row.line_bps = 100 * cpu / wall, (d.written - w0 + d.heard - h0) / wall
        d.write(feed.burst(i0 + k))
        cmd = feed.command(i0 + k)
        if cmd is not None:
            d.lc.publish(f"{VEHICLE}.{cmd[0]}", cmd[1])
        k += 1
    s = d.status[-1]
    before = dict(zip(s0.reason, s0.reason_count))
    dropped = {r: c - before.get(r, 0) for r, c in zip(s.reason, s.reason_count) if c > before.get(r, 0)}
    print(
        f"{feed.label} at {feed.rate_text}: {wall:.1f} s, {row.line_bps:.0f} B/s on the line, "
        f"{s.frames_decoded - s0.frames_decoded} frames (status at 1 Hz), dropped {dropped}; "
        f"{row.cpu_pct:.3f} % of a core"
    )


def bench(feed: Feed, lc: lcm.LCM, args: argparse.Namespace) -> Row:
    row = Row(feed)
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        if feed.fast == "replay":
            fast_replay(feed, row, tmp, args.fast_bytes)
        d = Driver(feed, tmp, lc)
        try:
            i0 = 0
            if feed.fast == "pty":
                i0 = fast_pty(d, row, args.fast_bytes)
            elif feed.fast == "lcm":
                fast_lcm(d, row, args.commands)
            at_rate(d, row, i0, args.seconds if args.quick else max(args.seconds, feed.min_seconds))
        except AssertionError:
            print(d.stderr.read_text()[-2000:], file=sys.stderr)
            raise
        finally:
            d.close()
        if args.verbose:
            print(d.stderr.read_text().rstrip(), file=sys.stderr)
    return row


def si(x: float) -> str:
    return "-" if x != x else f"{x / 1e6:.1f} M" if x >= 1e6 else f"{x / 1e3:.0f} k" if x >= 1e3 else f"{x:.0f}"


def table(rows: list[Row]) -> None:
    head = ("driver", "bytes/s parsed (max)", "frames/s (max)", "device rate", "line B/s", "CPU % at rate", "< 1 %")
    body = [
        (
            r.feed.label,
            f"{si(r.max_bps)}B/s" + ("" if r.how == "pty" else f" ({r.how})"),
            si(r.max_fps),
            r.feed.rate_text,
            f"{r.line_bps:.0f}",
            f"{r.cpu_pct:.3f}",
            "yes" if r.cpu_pct < 1.0 else "NO",
        )
        for r in rows
    ]
    widths = [max(len(x[i]) for x in [head, *body]) for i in range(len(head))]
    for line in [head, tuple("-" * w for w in widths), *body]:
        print("  ".join(x.ljust(w) for x, w in zip(line, widths)).rstrip())


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="short runs (rough figures)")
    ap.add_argument(
        "--driver", action="append", metavar="NAME", help="only this driver (gps, auv-ahrs, ...); repeatable"
    )
    ap.add_argument("--verbose", action="store_true", help="each driver's log (stderr) after its runs")
    ap.add_argument("--seconds", type=float, help="length of each device-rate run (default 20, --quick 3)")
    ap.add_argument(
        "--fast-bytes", type=int, help="bytes of each as-fast-as-possible run (default 16 MB, --quick 0.3 MB)"
    )
    ap.add_argument("--commands", type=int, help="actuators_t of the servo's fast run (default 50000, --quick 5000)")
    args = ap.parse_args()
    args.seconds = args.seconds or (3.0 if args.quick else 20.0)
    args.fast_bytes = args.fast_bytes or (300_000 if args.quick else 16_000_000)
    args.commands = args.commands or (5000 if args.quick else 50000)
    chosen = [f for f in feeds() if not args.driver or {f.program, f"auv-{f.program}"} & set(args.driver)]
    if not chosen:
        print(f"no driver named {args.driver}", file=sys.stderr)
        return 2
    missing = [f"auv-{f.program}" for f in chosen if not (BUILD / "bin" / f"auv-{f.program}").exists()]
    if missing:
        print(f"{', '.join(missing)} not built: run `make build`", file=sys.stderr)
        return 1
    lc = lcm.LCM(URL)
    rows = [bench(f, lc, args) for f in chosen]
    print()
    table(rows)
    return 0 if all(r.cpu_pct < 1.0 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())

"""auv-gps's cost (docs/drivers.md, "Cost"): NMEA written into a pseudo-terminal
as fast as the driver takes it (bytes per second parsed, fixes per second),
then at a receiver's real rate (GGA+RMC+GSA+VTG at 10 Hz, about 3 kB/s, more
than a 9600 baud line carries) for a few seconds: the driver's CPU per second
of device data, as a fraction of one core. Goal: well under 1 % of a core at
its device's rate. The CPU is the driver process's own (/proc/PID/schedstat)."""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from functools import reduce
from pathlib import Path

import lcm

from auv import driver_status_t, gps_fix_t
from auvlcm import programs

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("AUV_BUILD", ROOT / "build"))
if not BUILD.is_absolute():
    BUILD = ROOT / BUILD
URL = "udpm://239.255.76.67:7693?ttl=0"


def nmea(body: str) -> bytes:
    return f"${body}*{reduce(lambda a, c: a ^ ord(c), body, 0):02X}\r\n".encode()


def epoch(i: int, hz: int) -> bytes:
    s = i / hz
    tod = f"{int(s // 3600) % 24:02d}{int(s // 60) % 60:02d}{s % 60:05.2f}"
    return (
        nmea(f"GNRMC,{tod},A,4807.{i % 1000:03d},N,01131.000,E,001.9,084.4,150724,,,A")
        + nmea("GNVTG,084.4,T,,M,001.9,N,003.5,K,A")
        + nmea(f"GNGGA,{tod},4807.{i % 1000:03d},N,01131.000,E,1,09,1.1,12.5,M,46.9,M,,")
        + nmea("GNGSA,A,3,04,05,,09,12,,,24,,,,,2.5,1.1,2.1")
    )


def cpu_s(pid: int) -> float:
    """The process's time on a CPU: /proc/PID/schedstat counts nanoseconds
    (/proc/PID/stat counts 10 ms ticks: too coarse for a driver at 10 Hz)."""
    try:
        return int(Path(f"/proc/{pid}/schedstat").read_text().split()[0]) * 1e-9
    except (OSError, ValueError, IndexError):
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--epochs", type=int, default=20000, help="epochs in the as-fast-as-possible run")
    ap.add_argument("--seconds", type=float, default=10.0, help="length of the device-rate run")
    args = ap.parse_args()
    exe = BUILD / "bin" / "auv-gps"
    if not exe.exists():
        print(f"{exe} is not built: run `make build`", file=sys.stderr)
        return 1
    lc = lcm.LCM(URL)
    fixes = []
    status = []
    lc.subscribe("BENCH.GPS", lambda c, d: fixes.append(gps_fix_t.decode(d).utime))
    lc.subscribe("BENCH.DRIVER.GPS", lambda c, d: status.append(driver_status_t.decode(d)))
    with tempfile.TemporaryDirectory() as tmp:
        master, slave = os.openpty()
        link = Path(tmp) / "gps"
        os.symlink(os.ttyname(slave), link)
        os.close(slave)
        cmd = programs.device_driver(BUILD, "gps", vehicle="BENCH", lcm_url=URL, port=link, baud=115200)
        proc = subprocess.Popen(cmd + programs.gps_origin_flags(48.1, 11.5), stderr=subprocess.DEVNULL)
        try:
            time.sleep(0.5)  # the port open (the driver retries every 100 ms at first)
            data = b"".join(epoch(i, 10) for i in range(args.epochs))
            c0, t0 = cpu_s(proc.pid), time.monotonic()
            for i in range(0, len(data), 4096):
                os.write(master, data[i : i + 4096])
                while lc.handle_timeout(0):
                    pass
            # the driver's own counts (its 1 Hz status): a Python subscriber
            # would lose messages at this rate, the driver does not
            deadline = time.monotonic() + 120
            while time.monotonic() < deadline and not (status and status[-1].bytes_read >= len(data)):
                lc.handle_timeout(50)
            wall, cpu = time.monotonic() - t0, cpu_s(proc.pid) - c0
            s = status[-1]
            print(
                f"auv-gps as fast as it is fed: {s.bytes_read} bytes, {s.frames_decoded} sentences, "
                f"{s.messages_published} fixes published, {sum(s.reason_count)} dropped ({wall:.1f} s wall, "
                "status at 1 Hz)"
            )
            print(
                f"  {s.bytes_read / cpu / 1e6:.1f} MB/s parsed per CPU second ({cpu:.2f} s CPU, with LCM "
                f"publishing), {s.messages_published / cpu:.0f} fixes per CPU second"
            )
            # a receiver's real rate
            fixes.clear()
            c0, t0, i = cpu_s(proc.pid), time.monotonic(), 0
            sent = 0
            while time.monotonic() - t0 < args.seconds:
                e = epoch(args.epochs + i, 10)
                os.write(master, e)
                sent += len(e)
                i += 1
                next_t = t0 + i / 10.0
                while time.monotonic() < next_t:
                    lc.handle_timeout(max(1, int((next_t - time.monotonic()) * 1000)))
            wall, cpu = time.monotonic() - t0, cpu_s(proc.pid) - c0
            print(
                f"auv-gps at 10 Hz ({sent / wall:.0f} B/s of NMEA, {len(fixes)} fixes in {wall:.1f} s): "
                f"{100 * cpu / wall:.3f} % of a core; {1e6 * cpu / max(1, sent):.2f} us CPU per byte"
            )
            print(
                f"  at 9600 baud (960 B/s, the line full): {100 * 960 * cpu / max(1, sent):.3f} % of a core "
                f"(goal: well under 1 %)"
            )
        finally:
            proc.send_signal(signal.SIGTERM)
            proc.wait(10)
            os.close(master)
    return 0


if __name__ == "__main__":
    sys.exit(main())

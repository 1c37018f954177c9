"""The driver side of bench/driver_bench.py: a driver program on a pseudo-terminal, its
1 Hz status over LCM, the device's side of the terminal (answering what the driver
writes through its Feed), and the driver's CPU time."""

from __future__ import annotations

import os
import select
import signal
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

import lcm
from driver_feeds import VEHICLE, Feed

from auv import driver_status_t
from auvlcm import programs

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("AUV_BUILD", ROOT / "build"))
if not BUILD.is_absolute():
    BUILD = ROOT / BUILD
URL = "udpm://239.255.76.67:7693?ttl=0"


def cpu_s(pid: int) -> float:
    """The process's time on a CPU: /proc/PID/schedstat counts nanoseconds
    (/proc/PID/stat counts 10 ms ticks: too coarse for a driver at 10 Hz)."""
    try:
        return int(Path(f"/proc/{pid}/schedstat").read_text().split()[0]) * 1e-9
    except (OSError, ValueError, IndexError):
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


class Driver:
    """The driver on a pty, its status on LCM, the device's side of the pty."""

    def __init__(self, feed: Feed, tmp: Path, lc: lcm.LCM) -> None:
        self.feed, self.lc = feed, lc
        self.status: list[driver_status_t] = []
        self.master, slave = os.openpty()
        link = tmp / feed.program
        self.sub = lc.subscribe(f"{VEHICLE}.DRIVER.{feed.device}", lambda c, d: self._on_status(d, f"{link}@"))
        os.symlink(os.ttyname(slave), link)
        os.close(slave)
        cmd = programs.device_driver(
            BUILD, feed.program, vehicle=VEHICLE, lcm_url=URL, port=link, baud=feed.baud, extra=feed.flags(tmp)
        )
        self.stderr = tmp / f"{feed.program}.stderr"
        with open(self.stderr, "w") as err:
            self.proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
        self.written = 0  # bytes the device wrote to the driver
        self.heard = 0  # bytes the driver wrote to the device

    def _on_status(self, data: bytes, port: str) -> None:
        s = driver_status_t.decode(data)
        if s.port.startswith(port):  # not the last words of the previous run's driver
            self.status.append(s)

    def cpu(self) -> float:
        return cpu_s(self.proc.pid)

    def write(self, data: bytes) -> None:
        if data:
            os.write(self.master, data)
            self.written += len(data)

    def service(self, timeout: float = 0.0) -> None:
        """Wait up to timeout for the driver's bytes or LCM; answer the one, handle the other."""
        r, _, _ = select.select([self.master, self.lc.fileno()], [], [], max(0.0, timeout))
        if self.master in r:
            try:
                data = os.read(self.master, 4096)
            except OSError:  # EIO: the driver has not opened the terminal yet
                data = b""
            self.heard += len(data)
            self.write(self.feed.answer(data, time.time()) if data else b"")
        if self.lc.fileno() in r:
            self.lc.handle_timeout(0)
        self.write(self.feed.idle(time.time()))

    def wait(self, pred: Callable[[driver_status_t], bool], timeout: float) -> driver_status_t | None:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.status and pred(self.status[-1]):
                return self.status[-1]
            self.service(0.05)
        return None

    def next_status(self, timeout: float = 2.0) -> driver_status_t:
        """The next status the driver publishes (or the newest, after timeout)."""
        n = len(self.status)
        self.wait(lambda s: len(self.status) > n, timeout)
        return self.status[-1]

    def close(self) -> None:
        self.proc.send_signal(signal.SIGTERM)
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        os.close(self.master)
        self.lc.unsubscribe(self.sub)


def drops(s: driver_status_t) -> int:
    return sum(s.reason_count)

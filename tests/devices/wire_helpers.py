"""Helpers of the device tests: a reader on a port's far end, waiting for a condition."""

from __future__ import annotations

import os
import select
import time
from types import SimpleNamespace


def wait_until(cond, timeout: float = 5.0, what: str = "") -> None:
    deadline = time.monotonic() + timeout
    while not cond():
        if time.monotonic() > deadline:
            raise AssertionError(f"not within {timeout}s: {what}")
        time.sleep(0.005)


def pacer(warp: float = 1.0) -> SimpleNamespace:
    """What a WallClock reads of the simulator's pacer: sim 0 is now."""
    return SimpleNamespace(sim0=0.0, wall0=time.monotonic(), warp=warp)


def read_timed(fd: int, n: int, timeout: float = 10.0) -> list[tuple[float, bytes]]:
    """(monotonic time, bytes) of each read until n bytes came."""
    out: list[tuple[float, bytes]] = []
    got = 0
    deadline = time.monotonic() + timeout
    while got < n and time.monotonic() < deadline:
        if select.select([fd], [], [], 0.05)[0]:
            data = os.read(fd, 4096)
            out.append((time.monotonic(), data))
            got += len(data)
    return out


def drain(fd: int, quiet_s: float = 0.2) -> bytes:
    """Everything readable until quiet_s passes with nothing."""
    out = b""
    while select.select([fd], [], [], quiet_s)[0]:
        data = os.read(fd, 4096)
        if not data:
            break
        out += data
    return out

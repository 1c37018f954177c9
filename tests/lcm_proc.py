"""Helpers for tests that run real processes over real LCM."""

from __future__ import annotations

import os
import select
import signal
import subprocess
import sys
import time
from pathlib import Path

import lcm

LCM_BIN = Path(lcm.LCM_BIN_DIR).resolve()


def lcm_tool(name: str) -> str:
    """The real binary of an LCM tool (not the wheel's Python wrapper, which
    would leave the binary orphaned when the wrapper is killed)."""
    path = LCM_BIN / name
    assert path.exists(), f"{path} missing from the lcm wheel"
    return str(path)


def wait_for_line(proc: subprocess.Popen, text: str, timeout: float = 10.0) -> str:
    """Read proc's stdout until a line contains text; fail on timeout or exit.

    The pipe is read without blocking, and select() waits only when the text
    buffer is empty: a select() after a readline() could wait in vain for a
    line that readline() had already taken into the buffer (two lines written
    at once). What follows the line stays in proc.stdout for its next reader."""
    deadline = time.monotonic() + timeout
    fd = proc.stdout.fileno()
    blocking = os.get_blocking(fd)
    os.set_blocking(fd, False)
    seen: list[str] = []
    partial = ""
    try:
        while True:
            chunk = proc.stdout.readline()  # a line, the start of one, or "" when nothing is there
            if not chunk:
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                if not select.select([fd], [], [], min(left, 0.1))[0]:
                    continue
                chunk = proc.stdout.readline()
                if not chunk:
                    break  # readable with nothing to read: the end of its output
            partial += chunk
            if partial.endswith("\n"):
                seen.append(partial)
                if text in partial:
                    return partial
                partial = ""
    finally:
        os.set_blocking(fd, blocking)
    if partial:
        seen.append(partial)
    raise AssertionError(f"no line with {text!r} within {timeout}s; got {seen!r}")


def pump(lc: lcm.LCM, until, timeout: float = 10.0) -> bool:
    """Handle LCM messages until until() is true or timeout; returns until()."""
    deadline = time.monotonic() + timeout
    while not until() and time.monotonic() < deadline:
        lc.handle_timeout(50)
    return until()


def stop(proc: subprocess.Popen, sig: int = signal.SIGINT, timeout: float = 10.0) -> int:
    """Signal a process and wait for it; kill it if it does not end."""
    if proc.poll() is None:
        proc.send_signal(sig)
        try:
            proc.wait(timeout)
        except subprocess.TimeoutExpired:
            os.kill(proc.pid, signal.SIGKILL)
            proc.wait()
    return proc.returncode


def start_simulator(cfg: Path, env: dict, *extra: str) -> subprocess.Popen:
    """`python -m sim CFG` (stdout piped, merged with stderr), once it says it runs."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "sim", str(cfg), *extra],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=env,
    )
    wait_for_line(proc, "running", timeout=20)
    return proc

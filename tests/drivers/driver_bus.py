"""What every driver test needs around the real program: the LCM side (Bus:
what the driver publishes, as it arrives), the device side (Pty: a
pseudo-terminal behind a stable path), starting and stopping the driver, its
usage errors, and auv-driver-replay on the raw bytes it recorded."""

from __future__ import annotations

import math
import os
import re
import select
import signal
import socket
import struct
import subprocess
import threading
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import lcm
from conftest import c_program
from lcm_proc import pump, stop

from auv import driver_status_t, process_health_t, raw_bytes_t
from auvlcm import programs

VEHICLE = "AUV1"
# queues that hold a loaded run's bursts (LCM's default, 30, drops the newest)
QUEUE = 10000


class Bus:
    """What a driver publishes, as it arrives: `msgs` its messages of
    `msg_type` on <V>.<topic> (topic: the device name unless given), `status`
    its driver_status_t, `health` its process_health_t, `raw` its recorded
    bytes as (channel, data)."""

    def __init__(self, url: str, device: str, msg_type: Any = None, topic: str | None = None) -> None:
        self.lc = lcm.LCM(url)
        self.msgs: list[Any] = []
        self.status: list[driver_status_t] = []
        self.health: list[process_health_t] = []
        self.raw: list[tuple[str, bytes]] = []
        if msg_type is not None:
            self.collect(f"{VEHICLE}.{topic or device}", msg_type, self.msgs)
        self.collect(f"{VEHICLE}.DRIVER.{device}", driver_status_t, self.status)
        self.collect(f"{VEHICLE}.HEALTH", process_health_t, self.health)
        self.lc.subscribe(f"{VEHICLE}.RAW.{device}", lambda c, d: self.raw.append((c, d))).set_queue_capacity(QUEUE)

    def collect(self, channel: str, msg_type: Any, into: list) -> None:
        """Decode each message on channel as msg_type into the list."""
        self.lc.subscribe(channel, lambda c, d: into.append(msg_type.decode(d))).set_queue_capacity(QUEUE)

    def wait(self, until: Callable[[], Any], what: str, timeout: float = 20.0) -> None:
        assert pump(self.lc, until, timeout), f"waited {timeout} s for {what}; last status: {self.last()}"

    def last(self) -> driver_status_t | None:
        return self.status[-1] if self.status else None

    def reasons(self) -> dict[str, int]:
        s = self.last()
        return dict(zip(s.reason, s.reason_count)) if s else {}

    def reason(self, name: str) -> int:
        return self.reasons().get(name, 0)

    def wait_status(self, pred: Callable[[driver_status_t], Any], what: str, timeout: float = 20.0) -> driver_status_t:
        self.wait(lambda: bool(self.status) and pred(self.status[-1]), what, timeout)
        return self.status[-1]


class Pty:
    """A pseudo-terminal behind a stable path, as udev gives a device: swap()
    puts a new one behind the path and hangs the old one up (a device that
    vanished and came back)."""

    def __init__(self, link: Path) -> None:
        self.link = link
        self.master = -1
        self._new()

    def _new(self) -> None:
        master, slave = os.openpty()
        name = os.ttyname(slave)
        os.close(slave)  # the driver opens it itself
        tmp = self.link.with_suffix(".new")
        os.symlink(name, tmp)
        os.replace(tmp, self.link)
        old, self.master = self.master, master
        if old >= 0:
            os.close(old)

    def swap(self) -> None:
        self._new()

    def write(self, data: bytes) -> None:
        os.write(self.master, data)

    def close(self) -> None:
        if self.master >= 0:
            os.close(self.master)
            self.master = -1


class PtyDevice:
    """The device's side of a Pty, on a thread: each read of what the driver
    wrote goes to on_data(bytes); 50 ms without a byte, on_idle(). Both run
    under `lock`, so a test can act on the device between them."""

    def __init__(self, pty: Pty, on_data: Callable[[bytes], None], on_idle: Callable[[], None] = lambda: None) -> None:
        self.pty = pty
        self.on_data, self.on_idle = on_data, on_idle
        self.lock = threading.Lock()
        self.stop = False
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self) -> None:
        while not self.stop:
            r, _, _ = select.select([self.pty.master], [], [], 0.05)
            try:
                data = os.read(self.pty.master, 4096) if r else b""
            except OSError:  # EIO: no one has the terminal open (yet, or any more)
                time.sleep(0.05)
                continue
            with self.lock:
                if data:
                    self.on_data(data)
                else:
                    self.on_idle()

    def close(self) -> None:
        self.stop = True
        self.thread.join(2)


def free_tcp_port() -> int:
    """A TCP port nothing listens on now (for a simulator's server to take)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start(cmd: Sequence[str], tmp_path: Path, child_env: dict, name: str = "driver") -> subprocess.Popen:
    """The driver, its stderr in tmp_path/<name>.stderr for finish()."""
    err = open(tmp_path / f"{name}.stderr", "w")
    return subprocess.Popen(list(cmd), stdout=subprocess.DEVNULL, stderr=err, env=child_env)


def finish(proc: subprocess.Popen, tmp_path: Path, name: str = "driver") -> str:
    """Stop the driver: it must exit 0 on SIGTERM with no sanitizer report;
    its stderr."""
    rc = stop(proc, signal.SIGTERM)
    text = (tmp_path / f"{name}.stderr").read_text()
    assert rc == 0, f"exit {rc}:\n{text}"
    assert "runtime error" not in text and "Sanitizer" not in text, text
    return text


def check_usage_errors(program: str, cases: Sequence[tuple[list[str], str]], child_env: dict, base=()) -> None:
    """Each argument list (after base) exits 2 with its text on stderr."""
    exe = str(c_program(program))
    for args, text in cases:
        p = subprocess.run([exe, *base, *args], capture_output=True, text=True, env=child_env, timeout=30)
        assert p.returncode == 2 and text in p.stderr, (args, p.stderr)


def replay_print(
    tmp_path: Path, raw, child_env: dict, device: str, extra=(), sanitized: bool = False
) -> tuple[list[dict[str, str]], dict[str, int]]:
    """The recorded raw messages as a log, through auv-driver-replay --print:
    the printed messages' fields, and the summary's drops by reason."""
    log = lcm.EventLog(str(tmp_path / "raw.lcmlog"), "w", overwrite=True)  # one per call
    for channel, data in raw:
        log.write_event(raw_bytes_t.decode(data).utime, channel, data)
    log.close()
    build = c_program("bin/auv-driver-replay", sanitized).parent.parent
    cmd = programs.driver_replay(build, log=tmp_path / "raw.lcmlog", vehicle=VEHICLE, device=device, extra=list(extra))
    p = subprocess.run(cmd, capture_output=True, text=True, env=child_env, timeout=60)
    assert p.returncode == 0, p.stderr
    printed = []
    for line in p.stdout.splitlines():
        assert line.startswith(f"{VEHICLE}.{device} "), line
        printed.append(dict(re.findall(r'(\w+)=("(?:[^"\\]|\\.)*"|\S+)', line)))
    summary = p.stderr.strip().splitlines()[-1]  # "... N dropped: reason: n, reason: n"
    reasons = {k: int(v) for k, v in re.findall(r"[:,] ([a-z ]+): (\d+)", summary.rsplit(" dropped", 1)[1])}
    return printed, reasons


def raw_messages(device: str, chunks: Sequence[bytes], t0_us: int = 1_000_000, dt_us: int = 1_000_000):
    """Bytes a driver read, as its `--raw` recording: one raw_bytes_t per chunk,
    dt_us apart, on <VEHICLE>.RAW.<device> (what replay_print takes)."""
    out, offset = [], 0
    for k, data in enumerate(chunks):
        raw = raw_bytes_t()
        raw.utime, raw.vehicle, raw.device, raw.direction = t0_us + k * dt_us, VEHICLE, device, raw_bytes_t.DIR_RX
        raw.offset, raw.n_bytes, raw.data = offset, len(data), data
        offset += len(data)
        out.append((f"{VEHICLE}.RAW.{device}", raw.encode()))
    return out


def f32(x: float) -> float:
    """x as a float field holds it."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def same_printed(printed: dict[str, str], m: Any, f32_fields: Sequence[str] = ()) -> None:
    """A message as auv-driver-replay --print wrote it is m, field for field
    (f32_fields: float arrays, printed with 9 digits)."""
    for name in type(m).__slots__:
        value, text = getattr(m, name), printed[name]
        if isinstance(value, str):
            assert text == f'"{value}"', name
        elif isinstance(value, (list, tuple)):
            conv = f32 if name in f32_fields else float
            assert [conv(float(x)) for x in text.split(",")] == list(value), name
        elif isinstance(value, float) and math.isnan(value):
            assert text in ("nan", "-nan"), name
        else:
            assert float(text) == value, (name, text, value)

"""Helpers for the multi-HIL tests: start nodes and simulators, listen to a world."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from collections import defaultdict
from pathlib import Path

import lcm
import pytest
from conftest import ROOT

from auvlcm import programs
from auvlcm.rx import Receiver
from auvlcm.types import by_name
from auvlcm.url import with_receive_buffer
from sim.multihil.probe import load_probe, percentile, probe_errors  # noqa: F401  (for the tests)


class Proc:
    """A child process with its output in a file (read back by the test)."""

    def __init__(self, cmd: list, out: Path, env: dict) -> None:
        self.out = out
        self.p = subprocess.Popen(
            [str(c) for c in cmd], stdout=open(out, "w"), stderr=subprocess.STDOUT, env=env, start_new_session=True
        )

    def text(self) -> str:
        return self.out.read_text() if self.out.exists() else ""

    def wait_text(self, needle: str, timeout: float = 60.0) -> str:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            t = self.text()
            if needle in t:
                return t
            if self.p.poll() is not None:
                break
            time.sleep(0.05)
        raise AssertionError(f"{self.out.name}: no {needle!r} within {timeout}s:\n{self.text()}")

    def kill(self) -> None:
        if self.p.poll() is None:
            os.killpg(self.p.pid, signal.SIGKILL)
            self.p.wait()

    def stop(self, timeout: float = 15.0) -> int:
        if self.p.poll() is None:
            os.killpg(self.p.pid, signal.SIGINT)
            try:
                self.p.wait(timeout)
            except subprocess.TimeoutExpired:
                self.kill()
        return self.p.returncode


def node_cmd(node_id: str, url: str, priority: int = 0, *extra) -> list:
    return [
        sys.executable,
        "-m",
        "tools.launch.multihil_cli",
        "node",
        "--id",
        node_id,
        "--lcm-url",
        url,
        "--priority",
        str(priority),
        *extra,
    ]


def sim_cmd(config: Path, url: str, *extra) -> list:
    return programs.simulator(config, lcm_url=url, extra=["--multihil", *extra])


def vehicle_config(tmp: Path, vehicle: str, extra: str = "", base: str = "remus100_multihil.yaml", **initial) -> Path:
    """A simulator configuration for another vehicle id, from a shipped one."""
    text = (ROOT / "missions" / "sim" / base).read_text().replace("id: AUV1", f"id: {vehicle}")
    init = ", ".join(f"{k}: {v}" for k, v in initial.items())
    if init:
        text = text.replace("initial: {depth_m: 0.0}", f"initial: {{{init}}}")
    path = tmp / f"{vehicle}.yaml"
    path.write_text(text + extra)
    return path


class _Background:
    """An LCM instance handled by a thread of its own."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self._stop = False
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self._stop:
            self.lc.handle_timeout(20)

    def close(self) -> None:
        time.sleep(0.3)  # what is in flight
        self._stop = True
        self._thread.join(2.0)


class Listener(_Background):
    """Records the world's shared channels with wall receive times, from a
    thread of its own, so that receive times are true while the test waits."""

    CHANNELS = {
        "SIM.CLOCK": "sim_clock_t",
        "SIM.ENV_HEARTBEAT": "env_heartbeat_t",
        "SIM.ENV_ELECTION": "env_election_t",
        "SIM.ENV": "env_model_t",
    }

    def __init__(self, url: str, extra: dict[str, str] | None = None) -> None:
        super().__init__(url)
        self.rx = Receiver(self.lc)
        self.msgs: dict[str, list] = defaultdict(list)
        for ch, tname in {**self.CHANNELS, **(extra or {})}.items():
            self.rx.subscribe(ch, by_name(tname), self._on, queue_capacity=10000)
        self._thread.start()

    def _on(self, channel: str, msg) -> None:
        self.msgs[channel].append((time.monotonic(), msg))

    def pump(self, seconds: float, until=None) -> bool:
        """Wait up to `seconds`, or until until() is true."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            if until is not None and until():
                return True
            time.sleep(0.02)
        return until() if until is not None else True

    def servers(self, since: float = 0.0) -> set[str]:
        return {m.server_id for t, m in self.msgs["SIM.ENV_HEARTBEAT"] if t >= since}

    def last_server(self) -> tuple[str, int] | None:
        hb = self.msgs["SIM.ENV_HEARTBEAT"]
        return (hb[-1][1].server_id, hb[-1][1].term) if hb else None

    def clock_utimes(self) -> list[tuple[float, int, str]]:
        return [(t, m.utime, m.server_id) for t, m in self.msgs["SIM.CLOCK"]]


class Recorder(_Background):
    """Every message on a URL, raw, from a thread with a deep queue: a lossless
    record for byte comparisons (lcm-logger's default subscription queue drops
    messages when it is descheduled on a loaded machine)."""

    def __init__(self, url: str) -> None:
        super().__init__(with_receive_buffer(url))  # and a deep socket buffer: a burst while
        self.events: list[tuple[str, bytes]] = []  # the thread waits for a core is kept
        sub = self.lc.subscribe(".*", lambda ch, data: self.events.append((ch, data)))
        sub.set_queue_capacity(1_000_000)
        self._thread.start()


@pytest.fixture
def procs():
    """Processes a test starts (Proc), killed at its end; a stopped one (SIGSTOP,
    a frozen server) is continued first so that it can die. Tests import it."""
    started: list[Proc] = []
    yield started
    for p in started:
        if p.p.poll() is None:
            os.killpg(p.p.pid, signal.SIGCONT)
        p.kill()

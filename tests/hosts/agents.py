"""Helpers for the host-agent tests: start agents, talk to them over LCM."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import yaml
from conftest import ROOT

AGENT = [sys.executable, "-m", "tools.hosts.agent"]
AGENTCTL = [sys.executable, "-m", "tools.hosts.agentctl"]
SCEN = ROOT / "tests" / "tools" / "scenarios"
SIM = str(ROOT / "missions" / "sim" / "remus100_multihil.yaml")
BIND = str(ROOT / "missions" / "bindings" / "direct_actuators.bind")


def vehicle(vid: str, host: str, east: float = 0.0, cycles: int = 60) -> dict:
    nav = {
        "name": "NAVIGATOR",
        "plan": str(SCEN / "mission.chasm"),
        "bind": BIND,
        "rate": 10,
        "params": {"cycles": cycles},
    }
    watch = {"name": "WATCHER", "plan": str(SCEN / "watcher.chasm"), "bind": str(SCEN / "watcher.bind"), "rate": 5}
    return {"id": vid, "host": host, "sim": {"config": SIM, "initial": {"east_m": east}}, "managers": [nav, watch]}


def write_scenario(path: Path, vehicles: list, hosts: list, **extra) -> Path:
    sc = {
        "name": path.stem,
        "seed": 5,
        "time": {"mode": "lockstep", "limit": 60, "wall_limit": 120},
        "hosts": hosts,
        "vehicles": vehicles,
        **extra,
    }
    path.write_text(yaml.safe_dump(sc, sort_keys=False))
    return path


class AgentProc:
    def __init__(
        self, host: str, url: str, out: Path, env: dict, prefix: list | None = None, extra: tuple = ()
    ) -> None:
        self.host, self.log = host, out / f"agent.{host}.out"
        out.mkdir(parents=True, exist_ok=True)
        self.p = subprocess.Popen(
            [*(prefix or []), *AGENT, "--host", host, "--lcm-url", url, "--out", str(out / host), *extra],
            stdout=open(self.log, "w"),
            stderr=subprocess.STDOUT,
            env=env,
            start_new_session=True,
        )

    def text(self) -> str:
        return self.log.read_text()

    def stop(self, sig: int = signal.SIGTERM, timeout: float = 30.0) -> int:
        if self.p.poll() is None:
            os.kill(self.p.pid, sig)
            try:
                self.p.wait(timeout)
            except subprocess.TimeoutExpired:
                os.killpg(self.p.pid, signal.SIGKILL)
                self.p.wait()
        return self.p.returncode


def ctl(url: str, env: dict, *args: str, prefix: list | None = None, timeout: float = 90.0):
    return subprocess.run(
        [*(prefix or []), *AGENTCTL, *args, "--lcm-url", url], env=env, capture_output=True, text=True, timeout=timeout
    )


def alive(pid: int) -> bool:
    """True while pid exists and is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def wait_until(cond, timeout: float, what: str, step: float = 0.05):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        v = cond()
        if v:
            return v
        time.sleep(step)
    raise AssertionError(f"not within {timeout} s: {what}")


class Tables:
    """Every process table and ack the agents publish, heard on a thread."""

    def __init__(self, url: str, hosts: list[str]) -> None:
        import threading

        import lcm

        from auv import agent_ack_t, agent_table_t

        self.lc = lcm.LCM(url)
        self.history: dict[str, list] = {h: [] for h in hosts}  # (monotonic, table)
        self.acks: list = []
        self.lock = threading.Lock()
        for h in hosts:
            self.lc.subscribe(f"AGENT.{h}.PROCS", lambda _c, d, h=h: self._add(h, agent_table_t.decode(d)))
            self.lc.subscribe(f"AGENT.{h}.ACK", lambda _c, d: self._ack(agent_ack_t.decode(d)))
        self.done = False
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _add(self, h, t) -> None:
        with self.lock:
            self.history[h].append((time.monotonic(), t))

    def _ack(self, a) -> None:
        with self.lock:
            self.acks.append(a)

    def _run(self) -> None:
        while not self.done:
            self.lc.handle_timeout(50)

    def latest(self, host: str):
        with self.lock:
            return self.history[host][-1][1] if self.history[host] else None

    def rows(self, host: str) -> dict:
        t = self.latest(host)
        return {p.name: p for p in t.procs} if t else {}

    def publish(self, channel: str, msg) -> None:
        self.lc.publish(channel, msg.encode())

    def close(self) -> None:
        self.done = True
        self.thread.join()

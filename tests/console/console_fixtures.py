"""Fixtures for the console: a scenario running under the launcher, the console
serving it, and Debian's chromium (installed once when running as root, as CI
does; elsewhere the browser tests skip and say why)."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from conftest import BUILD, ROOT

SCENARIOS = ROOT / "tests" / "tools" / "scenarios"
SIM = ROOT / "missions" / "sim" / "remus100_multihil.yaml"
BIND = ROOT / "missions" / "bindings" / "direct_actuators.bind"
CONSOLE = [sys.executable, "-m", "tools.console"]
LAUNCH = [sys.executable, "-m", "tools.launch"]
ARTIFACTS = BUILD / "test-artifacts" / "console"


def _install_chromium() -> str:
    """apt-get install chromium when root and missing; the reason it is not there otherwise."""
    if os.geteuid() != 0:
        return "chromium is not installed and this is not root (apt-get install chromium)"
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    for cmd in (
        ["apt-get", "install", "-y", "--no-install-recommends", "chromium"],
        ["apt-get", "update"],
        ["apt-get", "install", "-y", "--no-install-recommends", "chromium"],
    ):
        print(f"console tests: {' '.join(cmd)}", file=sys.stderr)
        run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=900)
        if cmd[1] == "install" and run.returncode == 0 and shutil.which("chromium"):
            return ""
    return f"apt-get install chromium failed: {run.stderr.strip()[-300:]}"


@pytest.fixture(scope="session")
def chromium() -> str:
    exe = shutil.which("chromium")
    if exe is None:
        reason = _install_chromium()
        exe = shutil.which("chromium")
        if exe is None:
            print(f"\nconsole tests: browser tests skipped: {reason}", file=sys.stderr)
            pytest.skip(reason)
    return exe


def vehicle(vid: str, east: float = 0.0, cycles: int = 1_000_000) -> dict:
    nav = {
        "name": "NAVIGATOR",
        "plan": str(SCENARIOS / "mission.chasm"),
        "bind": str(BIND),
        "rate": 10,
        "params": {"cycles": cycles},
    }
    watch = {
        "name": "WATCHER",
        "plan": str(SCENARIOS / "watcher.chasm"),
        "bind": str(SCENARIOS / "watcher.bind"),
        "rate": 5,
    }
    return {"id": vid, "sim": {"config": str(SIM), "initial": {"east_m": east}}, "managers": [nav, watch]}


def write_scenario(tmp_path: Path, vehicles: list[dict], time: dict) -> Path:
    sc = {
        "name": "console_test",
        "seed": 5,
        "world": {"world": "console_bay", "bathymetry": "slope:depth=30,dn=0.05,de=0.02"},
        "time": time,
        "vehicles": vehicles,
    }
    path = tmp_path / "console_test.yaml"
    path.write_text(yaml.safe_dump(sc, sort_keys=False))
    return path


def read_until(proc: subprocess.Popen, text: str) -> str:
    """The first stdout line holding text (the process's output is line-buffered)."""
    lines = []
    for line in proc.stdout:
        lines.append(line)
        if text in line:
            return line
    raise AssertionError(f"no {text!r} in {lines}; exit {proc.wait()}")


class Console:
    def __init__(self, args: list[str], env: dict) -> None:
        self.proc = subprocess.Popen(
            CONSOLE + ["--port", "0", *args], env=env, text=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE
        )
        line = read_until(self.proc, "console: serving ")
        self.url = line.split("serving ", 1)[1].split()[0]

    def stop(self) -> int:
        self.proc.send_signal(signal.SIGTERM)
        try:
            return self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return self.proc.wait()


def stop_launcher(proc: subprocess.Popen) -> int:
    if proc.poll() is None:
        proc.send_signal(signal.SIGINT)
    try:
        return proc.wait(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        return proc.wait()

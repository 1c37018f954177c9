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


def write_run_log(path) -> None:
    """Two vehicles over 6 s of sim time: truth, nav, navigator status (running, then
    AUV2 aborted at 4 s), a contact, a heard modem frame, AUV1's frontseat (control
    granted, taken by an operator, given back); logged 50 ms apart."""
    import lcm as _lcm

    from auv import chasm_status_t, frontseat_status_t, ground_truth_t, modem_rx_t, nav_solution_t, sidescan_contact_t

    # AUV1 is a commercial vehicle: the frontseat gives the payload control at 1 s,
    # an operator takes it at 3 s (manual, mode M), and it comes back at 5 s
    frontseat = {}
    for t, state, mode, has, granted, lost in (
        (0.5, frontseat_status_t.STATE_FRONTSEAT, "N", False, 0, 0),
        (1.0, frontseat_status_t.STATE_PAYLOAD, "A", True, 1, 0),
        (3.0, frontseat_status_t.STATE_MANUAL, "M", False, 1, 1),
        (5.0, frontseat_status_t.STATE_PAYLOAD, "A", True, 2, 1),
    ):
        fs = frontseat_status_t()
        fs.utime, fs.vehicle, fs.protocol, fs.state, fs.mode = int(t * 1e6), "AUV1", "iver3", state, mode
        fs.has_control, fs.requesting, fs.control_granted, fs.control_lost = has, True, granted, lost
        fs.last_message_utime, fs.last_message_age_s = int(t * 1e6) - 100_000, 0.1
        frontseat[round(t * 10)] = fs
    log = _lcm.EventLog(str(path), "w", overwrite=True)
    for i in range(60):
        utime = i * 100_000
        for k, vid in enumerate(("AUV1", "AUV2")):
            tr = ground_truth_t()
            tr.utime, tr.vehicle, tr.eta = utime, vid, [i * 1.0, 20.0 * k, 5.0, 0.0, 0.0, 0.0]
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.north_m, nav.east_m = utime, vid, i * 1.0 + 0.5, 20.0 * k
            st = chasm_status_t()
            st.utime, st.vehicle, st.manager, st.cycle = utime, vid, "NAVIGATOR", i
            aborted = vid == "AUV2" and i >= 40
            st.run_state = 4 if aborted else 1
            st.active_path, st.path_len, st.time_in_state_s = (["emergency"] if aborted else ["run"]), 1, [0.0]
            for ch, m in ((f"{vid}.TRUTH", tr), (f"{vid}.NAV", nav), (f"{vid}.CHASM.NAVIGATOR", st)):
                log.write_event(1_000_000 + i * 50_000 + k, ch, m.encode())
        if i == 30:
            c = sidescan_contact_t()
            c.utime, c.vehicle, c.classification, c.north_m = utime, "AUV1", "mine_like", 12.0
            log.write_event(1_000_000 + i * 50_000 + 5, "AUV1.CONTACTS", c.encode())
            rx = modem_rx_t()
            rx.utime, rx.vehicle, rx.src_vehicle = utime, "AUV2", "AUV1"
            log.write_event(1_000_000 + i * 50_000 + 6, "AUV2.MODEM_RX", rx.encode())
        if i in frontseat:
            log.write_event(1_000_000 + i * 50_000 + 7, "AUV1.FRONTSEAT", frontseat[i].encode())
    log.close()

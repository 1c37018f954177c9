"""chasm-manager --status-rate: a status at most HZ times a second of mission
time, and one at once whenever the run state, the active path, the last
transition or a drop count changes; without it, one every cycle.

The test drives the clock a cycle at a time (0.1 s) and knows each cycle
ran from its setpoint (published every cycle), so it can tell which cycles
published a status and which did not."""

from __future__ import annotations

import signal
import subprocess

import lcm
import pytest
from conftest import ROOT, manager_cmd
from lcm_proc import pump, stop

from auv import chasm_status_t, nav_solution_t, setpoint_t, sim_clock_t
from auvlcm.rx import Receiver
from auvlcm.url import with_receive_buffer

HERE = ROOT / "tests" / "managers"
CYCLE_US = 100_000


class Driver:
    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(with_receive_buffer(url))
        self.rx = Receiver(self.lc)
        self.setpoints: list = []
        self.status: list = []
        self.rx.subscribe("AUV1.SETPOINT", setpoint_t, lambda c, m: self.setpoints.append(m), 1000)
        self.rx.subscribe("AUV1.CHASM.NAVIGATOR", chasm_status_t, lambda c, m: self.status.append(m), 1000)
        self.utime = 0

    def cycle(self, depth: float, raw_nav: bytes | None = None, wait: bool = True, expect: bool = False) -> None:
        """One cycle's clock (with a NAV fix before it); returns once its setpoint is
        out, and with expect once its status is too (however loaded the machine)."""
        self.utime += CYCLE_US
        nav = nav_solution_t()
        nav.utime, nav.vehicle, nav.depth_m = self.utime, "AUV1", depth
        self.lc.publish("AUV1.NAV", raw_nav if raw_nav is not None else nav.encode())
        clock = sim_clock_t()
        clock.utime, clock.server_id, clock.step_us = self.utime, "test", CYCLE_US
        self.lc.publish("SIM.CLOCK", clock.encode())
        t = self.utime
        if not wait:  # still starting: nothing is published before the plan runs
            pump(self.lc, lambda: bool(self.status) and self.status[-1].utime >= t, timeout=0.05)
            return
        assert pump(self.lc, lambda: bool(self.setpoints) and self.setpoints[-1].utime >= t, timeout=30), t
        # the status of that cycle, if any, follows its outputs: let it arrive
        pump(self.lc, lambda: bool(self.status) and self.status[-1].utime >= t, timeout=30 if expect else 0.2)

    def start(self) -> None:
        """Cycles until the plan runs (it waits for its first NAV)."""
        for _ in range(600):
            self.cycle(0.0, wait=False)
            if self.status and self.status[-1].run_state == chasm_status_t.RUN_RUNNING:
                return
        raise AssertionError("the manager never started its plan")


def run(url, env, *extra):
    cmd = manager_cmd(HERE / "dive.chasm", HERE / "vehicle.bind", url, *extra)
    return subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, text=True)


def test_a_status_rate_publishes_on_changes_and_at_most_at_the_rate(lcm_url, child_env):
    d = Driver(lcm_url)
    mgr = run(lcm_url, child_env, "--status-rate", "1")
    try:
        d.start()
        start = d.utime
        for _ in range(35):  # 3.5 s in `dive`: nothing changes
            d.cycle(1.0)
        quiet = [s.utime for s in d.status if s.utime > start]
        # one a second of mission time, on the cycle that completes the second
        assert [b - a for a, b in zip(quiet, quiet[1:])] == [1_000_000] * (len(quiet) - 1), quiet
        assert 3 <= len(quiet) <= 4, quiet
        assert all(s.active_path[-1] == "dive" for s in d.status[-len(quiet) :])
        # the transition to `hold`: its status comes at that very cycle
        before = len(d.status)
        d.cycle(9.0, expect=True)
        assert len(d.status) == before + 1 and d.status[-1].active_path[-1] == "hold"
        assert d.status[-1].utime == d.utime == d.status[-1].last_transition_utime
        # a message that fails to decode: the count moved, so a status at once
        d.cycle(9.0)
        before = len(d.status)
        d.cycle(9.0, raw_nav=b"\x00" * 12, expect=True)
        assert len(d.status) == before + 1 and d.status[-1].decode_errors == 1, [s.utime for s in d.status]
        # `hold` ends after 2 s: `finish`, at once, then quiet again
        for _ in range(25):
            d.cycle(9.0)
        finish = [s for s in d.status if s.active_path[-1:] == ["finish"]]
        assert finish and finish[0].last_transition_utime == finish[0].utime
        # the statuses carry the costliest step since the one before (CPU time, > 0)
        assert all(s.cycle_cost_us > 0 for s in d.status if s.run_state == chasm_status_t.RUN_RUNNING)
        cycles = len({s.utime for s in d.setpoints if s.utime > start})
        statuses = len([s for s in d.status if s.utime > start])
        assert statuses <= cycles // 4, (statuses, cycles)
    finally:
        rc = stop(mgr, signal.SIGTERM)
    assert rc == 0, mgr.stderr.read()


def test_without_a_status_rate_every_cycle_has_its_status(lcm_url, child_env):
    d = Driver(lcm_url)
    mgr = run(lcm_url, child_env)
    try:
        d.start()
        start = d.utime
        for _ in range(15):
            d.cycle(1.0)
        assert [s.utime for s in d.status if s.utime > start] == [start + CYCLE_US * (i + 1) for i in range(15)]
    finally:
        stop(mgr, signal.SIGTERM)


@pytest.mark.parametrize("value", ["-1", "nan", "2000", "x"])
def test_a_bad_status_rate_is_refused(value, lcm_url, child_env):
    cmd = manager_cmd(HERE / "dive.chasm", HERE / "vehicle.bind", lcm_url, "--status-rate", value)
    r = subprocess.run(cmd, env=child_env, capture_output=True, text=True, timeout=30)
    assert r.returncode == 2 and "--status-rate wants a number from 0 to 1000" in r.stderr, r.stderr


def test_an_on_change_output_goes_out_when_it_changes_and_once_a_second(lcm_url, child_env, tmp_path):
    """`on_change` after an output's type: the setpoint (set on each state's
    entry) is published at the cycle it changes, else once a second of mission
    time, with that cycle's utime; the status (every cycle) marks the cycles."""
    bind = tmp_path / "on_change.bind"
    bind.write_text((HERE / "vehicle.bind").read_text().replace("setpoint_t", "setpoint_t  on_change"))
    assert "on_change" in bind.read_text()
    lc = lcm.LCM(with_receive_buffer(lcm_url))
    rx = Receiver(lc)
    setpoints: list = []
    status: list = []
    rx.subscribe("AUV1.SETPOINT", setpoint_t, lambda c, m: setpoints.append(m), 1000)
    rx.subscribe("AUV1.CHASM.NAVIGATOR", chasm_status_t, lambda c, m: status.append(m), 1000)
    mgr = subprocess.Popen(
        manager_cmd(HERE / "dive.chasm", bind, lcm_url), env=child_env, stderr=subprocess.PIPE, text=True
    )
    utime = 0

    def cycle(depth: float) -> None:
        nonlocal utime
        utime += CYCLE_US
        nav = nav_solution_t()
        nav.utime, nav.vehicle, nav.depth_m = utime, "AUV1", depth
        lc.publish("AUV1.NAV", nav.encode())
        clock = sim_clock_t()
        clock.utime, clock.server_id, clock.step_us = utime, "test", CYCLE_US
        lc.publish("SIM.CLOCK", clock.encode())
        t = utime
        pump(lc, lambda: bool(status) and status[-1].utime >= t, timeout=30 if status else 0.05)

    try:
        for _ in range(600):
            cycle(0.0)
            if status and status[-1].run_state == chasm_status_t.RUN_RUNNING:
                break
        start = status[-1].utime
        for _ in range(25):  # `dive`: the same setpoint for 2.5 s
            cycle(1.0)
        cycle(9.0)  # `hold`: the speed changes at once
        hold_at = utime
        for _ in range(30):  # 2 s later `finish`
            cycle(9.0)
        assert status[-1].active_path[-1] == "finish"
    finally:
        stop(mgr, signal.SIGTERM)
    sent = [(m.utime, m.speed_mps, m.depth_m) for m in setpoints if m.utime >= start]
    times = [t for t, _, _ in sent]
    # never two within a second unless the second one changed something
    for (t0, *v0), (t1, *v1) in zip(sent, sent[1:]):
        assert t1 - t0 >= 1_000_000 or v1 != v0, (t0, t1, v0, v1)
        assert t1 - t0 <= 1_000_000, (t0, t1)  # and at least one a second
    assert hold_at in times and next(s for t, s, _ in sent if t == hold_at) == 1.0
    finish = [t for t, s, d in sent if s == 0.0 and d == 0.0]
    assert finish and finish[0] == next(st.last_transition_utime for st in status if st.active_path[-1:] == ["finish"])
    assert len(sent) <= 10, sent  # 6 s of cycles at 10 Hz: 60 without the flag

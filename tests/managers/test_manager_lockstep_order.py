"""A manager's cycle in lockstep sees the same inputs whatever order its
socket hears them in (issue 14, item 1: the same run under any load).

In step k every process publishes after it heard clock k, but the kernel
hands one multicast datagram to its member sockets one after the other: a
fast process can hear clock k, publish, and have its message of step k reach
another manager before clock k does (a loaded demo's recorder got 2 of
140 000 messages ahead of their clock; a team run diverged at a PILOT that way).
The manager holds such an input until its clock has come and the cycle of
that clock is done (c/managers/mgr_held.h). Here a test clock drives a real
chasm-manager over LCM twice: once with the input of step K sent after clock
K (the usual order), once sent before it. The setpoints must be the same.
"""

from __future__ import annotations

import subprocess
import time

import lcm
import pytest
from conftest import fresh_url, manager_cmd

from auv import lockstep_t, nav_solution_t, setpoint_t, sim_clock_t

STEP_US = 100_000
EARLY_STEP = 6  # NAV of this step and the next come ahead of this step's clock
LAST_STEP = 10

PLAN = """mission "order"
input  nav.depth_m        : double m
output setpoint.depth_m   : double m
test deep : nav.depth_m > 5 m
test shallow : nav.depth_m < 5 m
state wait {
    do set setpoint.depth_m = 1 m on entry
    when deep -> seen
}
state seen {
    do set setpoint.depth_m = 2 m on entry
    when shallow -> back
}
state back {
    do set setpoint.depth_m = 3 m on entry
}
"""
BIND = """input   nav       ${VEHICLE}.NAV        nav_solution_t
output  setpoint  ${VEHICLE}.SETPOINT   setpoint_t
"""


def fly(tmp_path, url: str, env: dict, sanitized: bool, early: bool) -> tuple[list[tuple[int, float]], str]:
    """Steps 1..LAST_STEP; NAV of step k is stamped t_k, deep only at EARLY_STEP.
    early: NAV of EARLY_STEP and of the step after it are sent before the clock
    of EARLY_STEP (one step ahead, two steps ahead). Returns the manager's
    setpoints (utime, depth) and its output."""
    (tmp_path / "order.chasm").write_text(PLAN)
    (tmp_path / "order.bind").write_text(BIND)
    cmd = manager_cmd(tmp_path / "order.chasm", tmp_path / "order.bind", url, sanitized=sanitized)
    lc = lcm.LCM(url)
    reports: list = []
    setpoints: list[tuple[int, float]] = []
    lc.subscribe("SIM.LOCKSTEP", lambda _c, d: reports.append(lockstep_t.decode(d))).set_queue_capacity(1000)
    lc.subscribe("AUV1.SETPOINT", lambda _c, d: setpoints.append(_setpoint(d))).set_queue_capacity(1000)
    proc = subprocess.Popen([str(c) for c in cmd], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

    def pump(seconds: float, until) -> bool:
        end = time.monotonic() + seconds
        while time.monotonic() < end and not until():
            lc.handle_timeout(20)
        return until()

    def done(step: int) -> bool:
        return any(m.kind == lockstep_t.KIND_STEP_DONE and m.step == step for m in reports)

    def clock(step: int) -> None:
        c = sim_clock_t()
        c.utime, c.server_id, c.mode, c.step, c.step_us = (
            step * STEP_US,
            "test",
            sim_clock_t.MODE_LOCKSTEP,
            step,
            STEP_US,
        )
        lc.publish("SIM.CLOCK", c.encode())

    def nav(step: int) -> None:
        n = nav_solution_t()
        n.utime, n.vehicle, n.depth_m = step * STEP_US, "AUV1", 10.0 if step == EARLY_STEP else 0.0
        lc.publish("AUV1.NAV", n.encode())

    try:
        assert pump(30, lambda: any(m.kind == lockstep_t.KIND_REGISTER for m in reports)), proc.poll()
        for step in range(1, LAST_STEP + 1):
            ahead = early and step in (EARLY_STEP, EARLY_STEP + 1)
            if early and step == EARLY_STEP:
                nav(step)  # same sender, so the manager's socket has them before the clock
                nav(step + 1)
            clock(step)
            assert pump(30, lambda: done(step)), f"no report of step {step}"
            if not ahead:
                nav(step)  # the usual order: after the manager's cycle of this clock
        pump(0.2, lambda: False)  # the last setpoints
    finally:
        proc.terminate()
        out = proc.communicate(timeout=30)[0]
    assert proc.returncode == 0, out
    return setpoints, out


def _setpoint(data: bytes) -> tuple[int, float]:
    m = setpoint_t.decode(data)
    return m.utime, m.depth_m


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_an_input_ahead_of_its_clock_waits_for_the_cycle_after_it(tmp_path, lcm_url, child_env, sanitized):
    usual, _ = fly(tmp_path, lcm_url, child_env, sanitized, early=False)
    ahead, out = fly(tmp_path, fresh_url(), child_env, sanitized, early=True)
    # the plan saw the deep NAV of step 6 at the cycle of step 7 and the
    # shallow one of step 7 at the cycle of step 8, in both orders
    assert next(t for t, depth in usual if depth == 2.0) == (EARLY_STEP + 1) * STEP_US, usual
    assert next(t for t, depth in usual if depth == 3.0) == (EARLY_STEP + 2) * STEP_US, usual
    assert ahead == usual
    assert "arrived before the clock of its step" in out, out
    assert "lockstep: 2 inputs arrived before their step's clock and waited for it, 0 applied" in out, out
    assert out.count("inputs arrived before their step's clock") == 1, out  # once, at exit: not per cycle

"""The simulator against hostile time stamps (issue 12, item 3), as a process over
real LCM: in stepped mode the test is the clock, so every step is exact.

Clocks and commands stamped at INT64_MAX, INT64_MIN, 10^18 and -1, a clock
that goes back or jumps once, commands from the future or out of order: each
is dropped, counted per reason in the summary line and logged once; the
simulator keeps following the good clock and the good command."""

from __future__ import annotations

import lcm
from lcm_proc import pump, stop
from test_hil_lcm import Recorder, start_sim

from auv import actuator_state_t, actuators_t, ground_truth_t, sim_clock_t

INT64_MAX, INT64_MIN = 2**63 - 1, -(2**63)
INVALID = (INT64_MAX, INT64_MIN, 10**18, -1)
STEP_US = 100_000


def clock_msg(utime: int, step: int = 0) -> bytes:
    c = sim_clock_t()
    c.utime, c.server_id, c.mode, c.step, c.step_us = utime, "test", sim_clock_t.MODE_LOCKSTEP, step, STEP_US
    return c.encode()


def command(utime: int, rpm: float, seq: int) -> bytes:
    a = actuators_t()
    a.utime, a.vehicle, a.prop_rpm, a.seq = utime, "AUV1", rpm, seq
    return a.encode()


def test_hostile_clocks_and_commands_are_dropped_counted_and_logged_once(tmp_path, child_env, lcm_url):
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    rec.sub("AUV1.TRUTH", ground_truth_t)
    rec.sub("AUV1.ACTUATOR_STATE", actuator_state_t)
    proc = start_sim(tmp_path, child_env, lcm_url, clock="lockstep", timeout=30.0)
    truth = rec.msgs["AUV1.TRUTH"]

    def step_to(k: int) -> None:
        lc.publish("SIM.CLOCK", clock_msg(k * STEP_US, k))
        assert pump(lc, lambda: truth and truth[-1].utime >= k * STEP_US, timeout=20)

    try:
        for k in range(21):
            step_to(k)
        now = 20 * STEP_US
        lc.publish("AUV1.ACTUATORS", command(now, 1000.0, 1))
        for i, bad in enumerate(INVALID):
            lc.publish("AUV1.ACTUATORS", command(bad, 0.0, 2 + i))
        lc.publish("AUV1.ACTUATORS", command(now + 5_000_000, 0.0, 10))  # from the future
        lc.publish("AUV1.ACTUATORS", command(now - 1_000_000, 0.0, 11))  # out of order
        for bad in INVALID:
            lc.publish("SIM.CLOCK", clock_msg(bad))
        lc.publish("SIM.CLOCK", clock_msg(now - 1_000_000))  # back by 1 s
        lc.publish("SIM.CLOCK", clock_msg(now + 100_000_000))  # 100 s ahead, once
        for k in range(21, 31):
            step_to(k)
        assert pump(lc, lambda: rec.msgs["AUV1.ACTUATOR_STATE"][-1].utime >= 30 * STEP_US)
        lc.handle_timeout(300)
    finally:
        assert stop(proc) == 0
    out = proc.stdout.read()
    times = [m.utime for m in truth]
    assert times == sorted(times) and times[-1] <= 30 * STEP_US + 20_000, times[-5:]
    states = [m for m in rec.msgs["AUV1.ACTUATOR_STATE"] if m.utime > now]
    assert states and all(m.last_command_utime == now for m in states)  # the good command holds
    assert "time drops: invalid 8, future 1, out_of_order 1, regression 1, jump 1" in out, out
    assert out.count("dropped a message") == 5, out  # one line per reason

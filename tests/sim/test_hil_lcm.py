"""The simulator as a process over real LCM (ttl=0): closed loop, clock modes,
stale commands, bad input, shutdown. Run inside tests/isolated_net.sh."""

from __future__ import annotations

import math
import signal
import subprocess
import sys
import time
from pathlib import Path

import lcm
import pytest
from lcm_proc import pump, start_simulator, stop
from lockstep import LockstepPilot

from auv import actuator_state_t, actuators_t, ground_truth_t, nav_solution_t, process_health_t, sim_clock_t
from auvlcm.rx import Receiver

ROOT = Path(__file__).resolve().parents[2]

CONFIG = """
vehicle: {{id: AUV1}}
simulation:
  clock: {clock}
  warp: {warp}
  truth_rate_hz: 10
  command_timeout_s: {timeout}
  on_stale: {on_stale}
  lcm_url: "{url}"
safe_command: {{rudder_rad: 0.0, stern_plane_rad: 0.0, prop_rpm: 0.0}}
initial: {{depth_m: 5.0, speed_mps: 1.5, prop_rpm: 1500, heading_rad: 0.0}}
environment:
  seed: 5
  bathymetry: "flat:depth=60"
  current: [{{depth_m: 0, north_mps: 0.1, east_mps: 0.0}}]
sensors:
  ahrs: {{rate_hz: 20}}
  depth: {{rate_hz: 10}}
  dvl: {{rate_hz: 5}}
  altimeter: {{rate_hz: 5}}
  gps: {{rate_hz: 1}}
  ins: {{rate_hz: {ins_rate}, bias: 0.0}}
"""


def start_sim(tmp_path, child_env, url, clock="scaled", warp=10.0, timeout=1.0, on_stale="hold", extra=(), ins_rate=20):
    cfg = tmp_path / "sim.yaml"
    cfg.write_text(
        CONFIG.format(clock=clock, warp=warp, timeout=timeout, on_stale=on_stale, url=url, ins_rate=ins_rate)
    )
    return start_simulator(cfg, child_env, *extra)


class Recorder:
    def __init__(self, lc):
        self.rx = Receiver(lc)
        self.msgs: dict[str, list] = {}

    def sub(self, channel, typ):
        self.msgs[channel] = []
        self.rx.subscribe(channel, typ, lambda ch, m: self.msgs[ch].append(m), queue_capacity=5000)


def test_closed_loop_holds_heading_and_depth(tmp_path, child_env, lcm_url):
    """A scripted controller steers by NAV and commands ACTUATORS over LCM: holds
    heading and changes depth from 5 m to 8 m. The test is the global clock and the
    pilot (tests/sim/lockstep.py: 0.04 s steps, INS at 25 Hz), exact under load."""
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    rec.sub("AUV1.TRUTH", ground_truth_t)
    rec.sub("AUV1.ACTUATOR_STATE", actuator_state_t)
    pilot = LockstepPilot(lc, "AUV1", depth_m=8.0)
    proc = start_sim(tmp_path, child_env, lcm_url, clock="lockstep", ins_rate=25)
    try:
        pilot.fly(60.0)
    finally:
        assert stop(proc) == 0
    out = proc.stdout.read()
    assert "stopped" in out and "no actuator command" not in out
    late = [m for m in rec.msgs["AUV1.TRUTH"] if m.utime > 40e6]
    # heading held at 0 against the prop torque's roll coupling
    heading_err = [abs((m.eta[5] + math.pi) % (2 * math.pi) - math.pi) for m in late]
    assert max(heading_err) < math.radians(5), max(heading_err)
    assert all(abs(m.eta[2] - 8.0) < 1.0 for m in late)
    assert late[-1].eta[0] > 60.0  # went north
    assert not rec.msgs["AUV1.ACTUATOR_STATE"][-1].command_stale


def test_stale_commands_go_to_the_safe_command_and_are_reported(tmp_path, child_env, lcm_url):
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    rec.sub("AUV1.ACTUATOR_STATE", actuator_state_t)
    proc = start_sim(tmp_path, child_env, lcm_url, warp=10.0, timeout=2.0, on_stale="safe")
    try:

        def send(rpm):
            cmd = actuators_t()
            cmd.vehicle, cmd.prop_rpm, cmd.utime = "AUV1", rpm, 1
            lc.publish("AUV1.ACTUATORS", cmd.encode())

        t_end = time.monotonic() + 1.0  # 10 sim s of commands at 1200 rpm
        while time.monotonic() < t_end:
            send(1200.0)
            lc.handle_timeout(20)
        fresh = rec.msgs["AUV1.ACTUATOR_STATE"][-1]
        assert pump(lc, lambda: rec.msgs["AUV1.ACTUATOR_STATE"][-1].command_stale, timeout=10)
        assert pump(lc, lambda: rec.msgs["AUV1.ACTUATOR_STATE"][-1].prop_rpm < 50, timeout=10)
    finally:
        assert stop(proc, signal.SIGTERM) == 0
    assert not fresh.command_stale and fresh.prop_rpm > 1100
    assert rec.msgs["AUV1.ACTUATOR_STATE"][-1].last_command_utime == 1
    assert "no actuator command" in proc.stdout.read()


def test_stepped_mode_follows_the_external_clock(tmp_path, child_env, lcm_url):
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    rec.sub("AUV1.TRUTH", ground_truth_t)
    rec.sub("SIM.CLOCK", sim_clock_t)
    proc = start_sim(tmp_path, child_env, lcm_url, clock="lockstep")
    try:
        t0 = 1_000_000_000  # the world is already at 1000 s
        clock = sim_clock_t()
        clock.server_id, clock.mode, clock.step_us = "test", sim_clock_t.MODE_LOCKSTEP, 100_000
        for k in range(0, 51):  # 5 s of global time, 0.1 s steps
            clock.utime, clock.step = t0 + k * 100_000, k
            lc.publish("SIM.CLOCK", clock.encode())
            time.sleep(0.01)
        assert pump(
            lc, lambda: rec.msgs["AUV1.TRUTH"] and rec.msgs["AUV1.TRUTH"][-1].utime >= t0 + 5_000_000, timeout=10
        )
        time.sleep(0.3)
        lc.handle_timeout(50)
        last = rec.msgs["AUV1.TRUTH"][-1].utime
        assert last <= t0 + 5_000_000 + 20_000, "ran ahead of the global clock"
    finally:
        assert stop(proc) == 0
    assert all(m.server_id == "test" for m in rec.msgs["SIM.CLOCK"])  # it never published one
    assert rec.msgs["AUV1.TRUTH"][0].utime >= t0


def test_bad_messages_are_counted_dropped_and_reported(tmp_path, child_env, lcm_url):
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    rec.sub("AUV1.HEALTH", process_health_t)
    rec.sub("AUV1.TRUTH", ground_truth_t)
    proc = start_sim(tmp_path, child_env, lcm_url, warp=5.0)
    try:
        good = actuators_t()
        good.vehicle = "AUV1"
        for _ in range(5):
            lc.publish("AUV1.ACTUATORS", b"\x00" * 7)  # truncated
            lc.publish("AUV1.ACTUATORS", ground_truth_t().encode())  # wrong type
            lc.publish("AUV1.ACTUATORS", good.encode()[:-3])  # cut short
        assert pump(lc, lambda: any(h.decode_errors >= 15 for h in rec.msgs["AUV1.HEALTH"]), timeout=10)
        n = len(rec.msgs["AUV1.TRUTH"])
        assert pump(lc, lambda: len(rec.msgs["AUV1.TRUTH"]) > n + 5, timeout=30)  # still running
        assert pump(lc, lambda: len(rec.msgs["AUV1.HEALTH"]) >= 3, timeout=10)
    finally:
        assert stop(proc) == 0
    h = rec.msgs["AUV1.HEALTH"][-1]
    assert h.process == "sim" and h.vehicle == "AUV1" and h.pid == proc.pid
    # paced by sim time, like every other output: one per health_period_s (1 s)
    times = [m.utime for m in rec.msgs["AUV1.HEALTH"]]
    assert len(times) >= 3 and all(b - a == 1_000_000 for a, b in zip(times, times[1:]))


def test_gaps_in_the_command_sequence_are_counted_as_overflows(tmp_path, child_env, lcm_url):
    """queue_overflows counts the commands we never saw (seq gaps), not a constant 0."""
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    rec.sub("AUV1.HEALTH", process_health_t)
    proc = start_sim(tmp_path, child_env, lcm_url, warp=5.0)
    try:
        cmd = actuators_t()
        cmd.vehicle, cmd.prop_rpm = "AUV1", 1000.0
        for seq in (1, 2, 5, 6, 10, 3):  # 3+3 missing; 3 after 10 is a pilot restart
            cmd.seq = seq
            lc.publish("AUV1.ACTUATORS", cmd.encode())
            time.sleep(0.02)
        assert pump(
            lc,
            lambda: any(h.queue_overflows == 5 and h.messages_received >= 6 for h in rec.msgs["AUV1.HEALTH"]),
            timeout=10,
        )
    finally:
        assert stop(proc) == 0
    assert max(h.queue_overflows for h in rec.msgs["AUV1.HEALTH"]) == 5


def test_config_error_exits_with_file_line_and_key(tmp_path, child_env):
    cfg = tmp_path / "bad.yaml"
    cfg.write_text("simulation:\n  clock: warp\n")
    res = subprocess.run(
        [sys.executable, "-m", "sim", str(cfg)], capture_output=True, text=True, env=child_env, timeout=60
    )
    assert res.returncode == 2
    assert f"{cfg}:2:10: simulation.clock:" in res.stderr


def test_non_local_url_is_refused(tmp_path, child_env):
    cfg = tmp_path / "far.yaml"
    cfg.write_text('simulation: {lcm_url: "udpm://239.255.76.67:7667?ttl=5"}\n')
    res = subprocess.run(
        [sys.executable, "-m", "sim", str(cfg)], capture_output=True, text=True, env=child_env, timeout=60
    )
    assert res.returncode == 2 and "ttl=5" in res.stderr


@pytest.mark.parametrize("channel", ["NAV_INS", "off"])
def test_ins_output_channel_moves_or_goes_off(tmp_path, child_env, lcm_url, channel):
    """sensors.ins.channel: the onboard filter can own <V>.NAV; the black-box INS
    publishes beside it (or nothing), and the other sensors are unchanged."""
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    for ch in ("AUV1.NAV", "AUV1.NAV_INS"):
        rec.sub(ch, nav_solution_t)
    rec.sub("AUV1.TRUTH", ground_truth_t)
    rec.sub("SIM.CLOCK", sim_clock_t)
    cfg = tmp_path / "sim.yaml"
    cfg.write_text(
        CONFIG.format(clock="scaled", warp=10.0, timeout=1.0, on_stale="hold", url=lcm_url, ins_rate=20).replace(
            "ins: {rate_hz: 20, bias: 0.0}", f"ins: {{rate_hz: 20, channel: {channel}}}"
        )
    )
    proc = start_simulator(cfg, child_env)
    try:
        assert pump(lc, lambda: len(rec.msgs["AUV1.TRUTH"]) >= 30, timeout=20)  # 3 sim s
    finally:
        assert stop(proc) == 0
    assert rec.msgs["AUV1.NAV"] == []
    clocks = rec.msgs["SIM.CLOCK"]  # it runs the world alone: it is the clock
    assert clocks and clocks[-1].mode == sim_clock_t.MODE_SCALED and clocks[-1].warp == 10.0
    assert all(b.utime > a.utime for a, b in zip(clocks, clocks[1:]))
    moved = rec.msgs["AUV1.NAV_INS"]
    if channel == "off":
        assert moved == []
    else:
        assert len(moved) >= 50 and all(m.source == nav_solution_t.SOURCE_SIM_INS for m in moved)

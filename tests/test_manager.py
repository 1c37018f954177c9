"""The generic manager runs a CHASM over real LCM: inputs bound from messages,
outputs published each cycle on the driven mission clock, status for lcm-spy,
decode errors counted, mission commands and plugin uploads acknowledged, and a
clean exit on SIGTERM."""

from __future__ import annotations

import hashlib
import signal
import subprocess
import time

import lcm
import pytest
from conftest import ROOT, manager_cmd
from lcm_proc import pump, stop

from auv import (
    chasm_status_t,
    chasm_structure_t,
    gps_fix_t,
    mission_ack_t,
    mission_command_t,
    nav_solution_t,
    plugin_upload_t,
    setpoint_t,
    sim_clock_t,
)
from auvlcm.rx import Receiver
from auvlcm.url import with_receive_buffer

HERE = ROOT / "tests" / "managers"
PERIOD_US = 100_000  # start_manager runs the manager at --rate 10


class World:
    """Drives SIM.CLOCK and AUV1.NAV, and records what the manager publishes."""

    def __init__(self, url: str) -> None:
        # A large socket buffer: the test publishes bursts (150 messages at a
        # time) that come back to its own socket with the manager's echoes,
        # and it reads only afterwards; the default 208 KiB dropped a status
        # in a stress run and the tick waited for it in vain.
        self.lc = lcm.LCM(with_receive_buffer(url))
        self.rx = Receiver(self.lc)
        self.setpoints: list = []
        self.status: list = []
        self.acks: list = []
        self.rx.subscribe("AUV1.SETPOINT", setpoint_t, lambda c, m: self.setpoints.append(m), 1000)
        self.rx.subscribe("AUV1.CHASM.NAVIGATOR", chasm_status_t, lambda c, m: self.status.append(m), 1000)
        self.rx.subscribe("AUV1.MISSION_ACK", mission_ack_t, lambda c, m: self.acks.append(m), 100)
        self.utime = 0
        self.term = 0  # the election term of the clock it sends

    def tick(self, dt_s: float, depth: float | None = None) -> None:
        """Advance the global clock (and send a NAV fix valid at that time).

        When the clock passes the manager's next cycle, wait for that cycle's
        status however long a loaded machine takes: status[-1] then always
        describes this tick, never an earlier one."""
        self.utime += int(dt_s * 1e6)
        if depth is not None:
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.depth_m = self.utime, "AUV1", depth
            self.lc.publish("AUV1.NAV", nav.encode())
        clock = sim_clock_t()
        clock.utime, clock.server_id, clock.step_us = self.utime, "test", int(dt_s * 1e6)
        clock.term = self.term
        self.lc.publish("SIM.CLOCK", clock.encode())
        if not self.status:  # not subscribed yet, or still starting: nothing is due
            pump(self.lc, lambda: bool(self.status), timeout=0.05)
            return
        due = self.status[-1].utime + PERIOD_US
        if self.utime >= due:
            assert pump(self.lc, lambda: self.status[-1].utime >= due, timeout=30), (
                f"the manager did not run its cycle at {due} us"
            )

    def command(self, cmd: int, seq: int, **fields) -> mission_ack_t:
        msg = mission_command_t()
        msg.utime, msg.vehicle, msg.seq, msg.command = self.utime, "AUV1", seq, cmd
        for k, v in fields.items():
            setattr(msg, k, v)
        self.lc.publish("AUV1.MISSION_CMD", msg.encode())
        assert pump(self.lc, lambda: any(a.seq == seq for a in self.acks), timeout=30), f"no ack {seq}"
        return next(a for a in self.acks if a.seq == seq)

    def wait_for_status(self, running: bool = True, timeout_s: float = 60.0) -> None:
        """Tick until the manager (which subscribes at start) publishes status;
        with running, until it has left LOADING (its inputs arrived)."""
        deadline = time.monotonic() + timeout_s
        while not (self.status and (not running or self.status[-1].run_state != chasm_status_t.RUN_LOADING)):
            assert time.monotonic() < deadline, "the manager never ran a cycle"
            self.tick(0.05, depth=0.0)

    def wait_for_first_cycle(self) -> None:
        self.wait_for_status(running=True)

    def leaf(self) -> str:
        return self.status[-1].active_path[-1]


def start_manager(url, env, sanitized=False, plan="dive.chasm", extra=(), bind="vehicle.bind"):
    cmd = manager_cmd(HERE / plan, HERE / bind, url, *extra, sanitized=sanitized)
    return subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, text=True)


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_manager_flies_the_plan_on_the_driven_clock(lcm_url, child_env, sanitized):
    w = World(lcm_url)
    mgr = start_manager(lcm_url, child_env, sanitized)
    try:
        w.wait_for_first_cycle()
        assert w.leaf() == "dive"
        assert w.setpoints[-1].depth_m == 10.0 and w.setpoints[-1].speed_mps == 1.5
        assert w.setpoints[-1].vehicle == "AUV1"
        for i in range(20):
            w.tick(0.05, depth=0.5 * i)
        assert w.leaf() == "hold" and w.setpoints[-1].speed_mps == 1.0
        last = w.status[-1]
        assert last.last_condition == "deep" and last.last_from == "dive" and last.last_to == "hold"
        assert dict(zip(last.test_name, last.test_value))["deep"] is True
        # Cycles run every 0.1 s of mission time: every second 0.05 s tick.
        times = [s.utime for s in w.status[-10:]]
        assert all(b - a == 100_000 for a, b in zip(times, times[1:])), times
        # A message that fails to decode is counted, and the mission goes on.
        w.lc.publish("AUV1.NAV", b"\x00" * 12)
        for _ in range(50):
            w.tick(0.05, depth=9.0)
        assert w.status[-1].decode_errors == 1
        assert w.leaf() == "finish" and w.setpoints[-1].depth_m == 0.0
        assert w.status[-1].time_in_state_s[-1] == pytest.approx(0.5 * 50 * 0.1 - 2.0, abs=0.31)
    finally:
        rc = stop(mgr, signal.SIGTERM)
    err = mgr.stderr.read()
    assert rc == 0, err
    assert "NAVIGATOR: stopped" in err


def test_stale_input_aborts_through_the_plan(lcm_url, child_env):
    w = World(lcm_url)
    mgr = start_manager(lcm_url, child_env)
    try:
        w.wait_for_first_cycle()
        for _ in range(80):  # 4 s with a clock but no navigation
            w.tick(0.05)
        assert w.leaf() == "surface"
        assert w.status[-1].last_condition == "stale"
        assert w.setpoints[-1].vertical_mode == setpoint_t.VERTICAL_PITCH
    finally:
        assert stop(mgr, signal.SIGINT) == 0


def test_mission_commands_are_acknowledged(lcm_url, child_env):
    w = World(lcm_url)
    mgr = start_manager(lcm_url, child_env)
    try:
        w.wait_for_first_cycle()
        assert w.command(mission_command_t.CMD_PAUSE, 1).result == mission_ack_t.RESULT_OK
        w.tick(0.1, depth=0.0)
        assert w.status[-1].run_state == chasm_status_t.RUN_PAUSED
        assert w.command(mission_command_t.CMD_RESUME, 2).message == "resumed"
        w.tick(0.1, depth=0.0)
        assert w.status[-1].run_state == chasm_status_t.RUN_RUNNING
        assert w.command(mission_command_t.CMD_ABORT, 3, reason="test").message == "aborting"
        w.tick(0.1, depth=0.0)
        assert w.leaf() == "surface"
        bad = (HERE / "dive.chasm").read_text().replace("nav.depth_m >", "nav.depht_m >")
        ack = w.command(mission_command_t.CMD_LOAD_PLAN, 4, plan_name="bad.chasm", plan_text=bad)
        assert ack.result == mission_ack_t.RESULT_REJECTED
        w.tick(0.1, depth=0.0)
        assert w.leaf() == "surface", "a rejected plan must leave the mission untouched"
        good = (HERE / "dive.chasm").read_text()
        assert (
            w.command(mission_command_t.CMD_LOAD_PLAN, 5, plan_name="new.chasm", plan_text=good).result
            == mission_ack_t.RESULT_OK
        )
        w.tick(0.1, depth=0.0)
        w.tick(0.1, depth=0.0)
        assert w.leaf() == "dive"
        assert w.command(mission_command_t.CMD_STOP, 6).message == "stopping"
        assert mgr.wait(10) == 0
    finally:
        stop(mgr)


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_the_plan_structure_travels_with_the_status(lcm_url, child_env, sanitized):
    """<VEHICLE>.PLAN.<NAME>: the plan's structure with the first status, again
    every 10 s of mission time, and a new one (a new plan_id) on LOAD_PLAN; every
    status names it and carries the live values of the active transitions' tests."""
    w = World(lcm_url)
    plans: list = []
    w.rx.subscribe("AUV1.PLAN.NAVIGATOR", chasm_structure_t, lambda c, m: plans.append(m), 100)
    mgr = start_manager(lcm_url, child_env, sanitized)
    try:
        w.wait_for_first_cycle()
        assert len(plans) == 1
        p = plans[0]
        assert p.plan == "dive.chasm" and len(p.plan_id) == 16 and not p.truncated
        assert list(p.state_path) == ["dive", "hold", "finish", "surface"] and list(p.state_parent) == [-1] * 4
        assert p.state_loc[0].endswith("dive.chasm:14:7")
        # the abort first (from -1), then each state's
        assert list(zip(p.trans_from, p.trans_to, p.trans_condition)) == [
            (-1, 3, "stale"),
            (0, 1, "deep"),
            (1, 2, "elapsed > 2 s"),
        ]
        assert list(p.trans_test_name) == ["stale", "deep"] and list(p.trans_n_tests) == [1, 1, 0]
        assert "setpoint.depth_m" in p.var_name and p.action_time_model[0] == "entry"
        st = w.status[-1]
        assert st.plan_id == p.plan_id
        assert list(st.live_test_value) == [False, False]  # stale, then dive's deep
        w.tick(0.1, depth=6.0)
        w.tick(0.1, depth=6.0)
        assert w.leaf() == "hold" and w.status[-1].n_live_tests == 1  # stale; hold's elapsed names no test
        for _ in range(21):
            w.tick(0.5, depth=6.0)
        assert len(plans) == 2 and plans[1].plan_id == p.plan_id  # sent again for late listeners
        text = (
            (HERE / "dive.chasm")
            .read_text()
            .replace("state finish", "state done_here")
            .replace("-> finish", "-> done_here")
        )
        ack = w.command(mission_command_t.CMD_LOAD_PLAN, 7, plan_name="new.chasm", plan_text=text)
        assert ack.result == mission_ack_t.RESULT_OK
        w.tick(0.1, depth=0.0)
        w.tick(0.1, depth=0.0)
        assert pump(w.lc, lambda: len(plans) == 3, timeout=10)
        assert plans[2].plan == "new.chasm" and plans[2].plan_id != p.plan_id
        assert "done_here" in plans[2].state_path
        assert w.status[-1].plan_id == plans[2].plan_id
        assert w.status[-1].plan == "new.chasm"  # the status names the plan that runs, not the first
    finally:
        stop(mgr)


def test_a_structure_too_big_to_send_says_so(lcm_url, child_env, tmp_path):
    """A plan whose structure would encode to over 1 MiB: the header alone, truncated,
    with the reason; the plan runs and its statuses still name the structure."""
    head = (HERE / "dive.chasm").read_text().split("state dive")[0]
    states = "".join(f"state s{i:05d}_a_name_long_enough_to_fill_the_table {{\n}}\n" for i in range(12000))
    (tmp_path / "big.chasm").write_text(head + "state dive {\n}\nstate surface {\n}\n" + states)
    w = World(lcm_url)
    plans: list = []
    w.rx.subscribe("AUV1.PLAN.NAVIGATOR", chasm_structure_t, lambda c, m: plans.append(m), 100)
    mgr = subprocess.Popen(
        manager_cmd(tmp_path / "big.chasm", HERE / "vehicle.bind", lcm_url),
        env=child_env,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        w.wait_for_first_cycle()
        assert pump(w.lc, lambda: bool(plans), timeout=10)
        p = plans[0]
        assert p.truncated and p.n_states == 0 and p.n_transitions == 0
        assert "12002 states encode to" in p.note and "over the 1048576" in p.note, p.note
        assert w.status[-1].plan_id == p.plan_id and w.leaf() == "dive"
    finally:
        stop(mgr)


def test_plugin_uploads_are_checked_before_anything_is_written(lcm_url, child_env, tmp_path):
    plugin_dir = tmp_path / "plugins"
    plugin_dir.mkdir()
    allow = tmp_path / "allowlist"
    data = b"\x7fELF not really a plugin"
    allow.write_text(hashlib.sha256(data).hexdigest() + " fake\n")
    w = World(lcm_url)
    mgr = start_manager(lcm_url, child_env, extra=["--plugin-dir", plugin_dir, "--allowlist", allow])
    try:
        w.wait_for_first_cycle()

        def upload(seq: int, payload: bytes, digest: str) -> mission_ack_t:
            up = plugin_upload_t()
            up.utime, up.vehicle, up.seq, up.plugin_name, up.plugin_version = w.utime, "AUV1", seq, "fake", "1"
            up.sha256_hex, up.n_bytes, up.data = digest, len(payload), payload
            w.lc.publish("AUV1.PLUGIN_UPLOAD", up.encode())
            assert pump(w.lc, lambda: any(a.seq == seq for a in w.acks), timeout=30)
            return next(a for a in w.acks if a.seq == seq)

        ack = upload(10, data, "0" * 64)
        assert ack.result == mission_ack_t.RESULT_REJECTED and "does not match" in ack.message
        other = b"another file"
        ack = upload(11, other, hashlib.sha256(other).hexdigest())
        assert ack.result == mission_ack_t.RESULT_REJECTED and "allowlist" in ack.message
        assert list(plugin_dir.iterdir()) == []
        ack = upload(12, data, hashlib.sha256(data).hexdigest())  # allowed, but not a plugin
        assert ack.result == mission_ack_t.RESULT_FAILED and "mission unchanged" in ack.message
        w.tick(0.1, depth=0.0)
        assert w.leaf() == "dive"
    finally:
        assert stop(mgr, signal.SIGTERM) == 0


@pytest.mark.parametrize(
    "plan_edit,error",
    [
        (("nav.depth_m > 5", "nav.depht_m > 5"), None),
        (
            ("input  nav.vehicle        : string", "input  nav.vehicle : string\ninput nav.depht_m : double m"),
            "vehicle.bind:2:1: plan variable 'nav.depht_m': nav_solution_t has no field 'depht_m' (did you mean 'depth_m'?)",
        ),
        (
            ("input  nav.vehicle        : string", "input  nav.vehicle : string\noutput gps.fix_m : double m"),
            "plan output 'gps.fix_m' has no binding",
        ),
        (
            ("input  nav.vehicle        : string", "input  nav.status        : string"),
            "plan variable 'nav.status' is a string but the field is a number",
        ),
    ],
)
def test_plans_and_bindings_that_do_not_fit_are_refused(tmp_path, lcm_url, child_env, plan_edit, error):
    text = (HERE / "dive.chasm").read_text()
    assert plan_edit[0] in text
    plan = tmp_path / "p.chasm"
    plan.write_text(text.replace(*plan_edit))
    run = subprocess.run(
        manager_cmd(plan, HERE / "vehicle.bind", lcm_url),
        env=child_env,
        capture_output=True,
        text=True,
        timeout=20,
    )
    assert run.returncode == 1
    assert (error or "p.chasm:") in run.stderr


def test_an_optional_input_does_not_hold_the_start(lcm_url, child_env):
    """GPS only exists at the surface: a plan reading it starts on NAV alone,
    and sees the first fix when it comes."""
    w = World(lcm_url)
    mgr = start_manager(lcm_url, child_env, plan="gps_fix.chasm", bind="gps_optional.bind")
    try:
        w.wait_for_first_cycle()
        assert w.status[-1].run_state == chasm_status_t.RUN_RUNNING and w.leaf() == "dive"
        for _ in range(40):
            w.tick(0.05, depth=0.0)
        assert w.leaf() == "wait_fix", "no GPS yet: the fix test must be false"
        fix = gps_fix_t()
        fix.utime, fix.vehicle, fix.fix_type = w.utime, "AUV1", gps_fix_t.FIX_3D
        w.lc.publish("AUV1.GPS", fix.encode())
        for _ in range(6):
            w.tick(0.05, depth=0.0)
        assert w.leaf() == "on_top" and w.status[-1].last_condition == "fixed"
    finally:
        assert stop(mgr, signal.SIGTERM) == 0


def test_a_required_input_holds_the_start(lcm_url, child_env, tmp_path):
    """Without `optional`, the same plan waits (LOADING) for a GPS message."""
    bind = tmp_path / "strict.bind"
    bind.write_text((HERE / "gps_optional.bind").read_text().replace("optional", ""))
    w = World(lcm_url)
    mgr = start_manager(lcm_url, child_env, plan="gps_fix.chasm", bind=bind)
    try:
        w.wait_for_status(running=False)
        for _ in range(30):
            w.tick(0.05, depth=0.0)
        assert w.status, "the manager publishes LOADING status while it waits"
        assert {s.run_state for s in w.status} == {chasm_status_t.RUN_LOADING}
    finally:
        assert stop(mgr, signal.SIGTERM) == 0


@pytest.mark.parametrize(
    "line,error",
    [
        ("input gps ${VEHICLE}.GPS gps_fix_t maybe", "strict.bind:1:36: the only flag after the type is `optional`"),
        ("output gps ${VEHICLE}.GPS gps_fix_t optional", "strict.bind:1:37: only an input can be optional"),
        ("input gps ${VEHICLE}.GPS gps_fix_t on_change", "strict.bind:1:36: only an output can be on_change"),
    ],
)
def test_bad_binding_flags_are_refused(tmp_path, lcm_url, child_env, line, error):
    bind = tmp_path / "strict.bind"
    bind.write_text(line + "\n" + (HERE / "vehicle.bind").read_text())
    run = subprocess.run(
        manager_cmd(HERE / "gps_fix.chasm", bind, lcm_url),
        env=child_env,
        capture_output=True,
        text=True,
        timeout=20,
    )
    assert run.returncode == 1
    assert error in run.stderr, run.stderr

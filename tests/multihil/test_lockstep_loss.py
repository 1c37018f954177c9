"""Lockstep survives lost datagrams (issue 14): every wait of the protocol is
repeated, never waited for for ever.

- the protocol alone (no network): a lost STEP_DONE is repeated by its
  participant; a lost clock shows as a participant repeating the step before,
  and the server publishes the step again; repeats change nothing;
- the launcher's clock (tools/launch/worldclock.py) over real LCM with two Python
  participants whose traffic a test hook drops (a REGISTER, a clock, a report):
  time still reaches its end;
- the C participants (a manager, auv-nav, normal and sanitized builds) repeat
  their last report while no newer clock comes, and the filter reports a step
  only after its simulator did.
"""

from __future__ import annotations

import subprocess
import time

import lcm
import pytest
from conftest import ROOT, c_program, manager_cmd

from auv import lockstep_t, sim_clock_t
from auvlcm import programs
from auvlcm.chanfilter import FilteredLcm
from sim.multihil.lockstep import LockstepTracker, Participation, lockstep_msg
from sim.multihil.server import LockstepServer
from tools.launch.worldclock import WorldClock

K = lockstep_t


def test_lost_reports_and_clocks_are_repeated_until_the_world_goes_on():
    tracker = LockstepTracker(timeout_s=None)
    server = LockstepServer(tracker, 100_000, 2, expect_names={"A", "B"})
    wire: list = []  # what the participants sent
    parts = {n: Participation(n, wire.append, resend_s=0.0) for n in "AB"}
    for p in parts.values():
        p.poll()  # REGISTER
    for m in wire:
        tracker.on_message(m)
    wire.clear()
    assert server.poll() == 0
    clocks = [0]
    lose_clock = {("A", 3)}  # A never gets the clock of step 3 the first time
    lose_report = {("B", 5)}  # B's first report of step 5 is lost
    for _ in range(200):
        step = clocks[-1]
        for name, p in parts.items():
            if (name, step) in lose_clock:
                lose_clock.discard((name, step))
                continue
            p.on_clock(step, step * 100_000)
            p.done()
        for p in parts.values():
            p.poll()  # repeats what no newer clock answered
        for m in wire:
            if (m.participant, m.step) in lose_report and m.kind == K.KIND_STEP_DONE:
                lose_report.discard((m.participant, m.step))
                continue
            tracker.on_message(m)
        wire.clear()
        if all(p.last_done == 10 for p in parts.values()):
            break
        nxt = server.poll()
        if nxt is not None:
            clocks.append(nxt)
    assert clocks[-1] == 10, clocks
    assert server.republished >= 1 and clocks.count(3) >= 2  # step 3 went out again
    assert sorted(set(clocks)) == list(range(11))  # never skipped, never back
    assert all(b >= a for a, b in zip(clocks, clocks[1:]))
    assert parts["A"].last_done == parts["B"].last_done == 10


def test_a_repeated_clock_is_only_acknowledged():
    sent: list = []
    p = Participation("A", sent.append)
    p.on_clock(4, 400_000)
    p.done()
    p.on_clock(4, 400_000)  # the same step again (a repeat)
    assert p.pending is None and [m.step for m in sent] == [4, 4]
    tracker = LockstepTracker(timeout_s=None)
    for m in sent:
        tracker.on_message(m)
    assert tracker.parts["A"].last_done == 4 and tracker.repeats == 1


class Lossy:
    """A Python participant on real LCM whose in- and outgoing lockstep traffic
    a test hook drops: `drop_in` (steps whose clock it does not hear the first
    time), `drop_out` (reports lost the first time), and its first REGISTER."""

    def __init__(self, url: str, name: str, drop_in: set[int], drop_out: set[int]) -> None:
        self.lc = lcm.LCM(url)
        self.drop_in, self.drop_out = set(drop_in), set(drop_out)
        self.register_lost = False
        self.part = Participation(name, self._send, resend_s=0.1)
        self.lc.subscribe("SIM.CLOCK", self._on_clock).set_queue_capacity(1000)

    def _send(self, m) -> None:
        if m.kind == K.KIND_REGISTER and not self.register_lost:
            self.register_lost = True
            return
        if m.kind == K.KIND_STEP_DONE and m.step in self.drop_out:
            self.drop_out.discard(m.step)
            return
        self.lc.publish("SIM.LOCKSTEP", m.encode())

    def _on_clock(self, _ch: str, data: bytes) -> None:
        c = sim_clock_t.decode(data)
        if c.step in self.drop_in:
            self.drop_in.discard(c.step)
            return
        self.part.on_clock(c.step, c.utime)
        self.part.done()

    def turn(self) -> None:
        self.part.poll()
        self.lc.handle_timeout(5)


@pytest.mark.parametrize("receiver", ["liblcm", "own socket"])
def test_the_launchers_clock_does_not_stall_on_lost_datagrams(lcm_url, receiver):
    """Through liblcm the clock tracks every report in Python; on its own
    socket a board in C takes the ordinary ones (auvlcm/lockstep_board.py)
    and Python only the rest: the repeats that a loss causes among them."""
    lc = lcm.LCM(lcm_url) if receiver == "liblcm" else FilteredLcm(lcm_url)
    if receiver != "liblcm" and lc._own is None:
        pytest.skip("no own socket here (libauvlcm_sender.so not built, or AUV_LCM_READER=0)")
    clock = WorldClock(lc, "lockstep", 1.0, 0.05, {"AUV1.sim", "AUV1.PILOT"})
    assert (clock.board is None) == (receiver == "liblcm")
    a = Lossy(lcm_url, "AUV1.sim", drop_in={3, 17}, drop_out={8})
    b = Lossy(lcm_url, "AUV1.PILOT", drop_in={8}, drop_out={3, 20})
    deadline = time.monotonic() + 60
    while not clock.ready() and time.monotonic() < deadline:
        a.turn(), b.turn()
        lc.handle_timeout(5)
    assert clock.ready(), clock.not_ready()
    clock.start()
    while clock.now_us < 1_500_000 and time.monotonic() < deadline:
        clock.advance()
        a.turn(), b.turn()
        lc.handle_timeout(int(clock.wait_s() * 1000) // 10 + 1)
    assert clock.now_us >= 1_500_000, (clock.now_us, clock.waiting_for())
    assert not (a.drop_in or a.drop_out or b.drop_in or b.drop_out)  # every loss happened
    assert clock.server.republished >= 3  # steps 3, 8, 17 went out again
    assert a.part.resent and b.part.resent
    if clock.board is not None:
        assert clock.board.taken >= 40  # most of the 60 reports never reached Python


def test_the_launchers_clock_blocks_instead_of_spinning(lcm_url):
    """While it waits for a participant, the launcher sleeps on the LCM descriptor."""
    clock = WorldClock(lcm.LCM(lcm_url), "lockstep", 1.0, 0.05, {"AUV1.sim"})
    clock.start()
    assert clock.wait_s() > 0.1


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_c_participants_repeat_reports_and_the_filter_waits_for_its_simulator(lcm_url, child_env, tmp_path, sanitized):
    build = ROOT / "build" / ("san" if sanitized else "")
    mgr = manager_cmd(
        ROOT / "tests/tools/scenarios/mission.chasm",
        ROOT / "missions/bindings/direct_actuators.bind",
        lcm_url,
        "-D",
        "cycles=1000",
        "--plugin-path",
        build / "plugins",
        sanitized=sanitized,
    )
    nav_conf = tmp_path / "AUV1.nav"
    from sim.config import load
    from tools.nav.navconf import nav_config_text

    nav_conf.write_text(nav_config_text(load(ROOT / "missions/sim/remus100.yaml")))
    nav = programs.auv_nav(
        c_program("bin/auv-nav", sanitized).parents[1], config=nav_conf, vehicle="AUV1", lcm_url=lcm_url
    )
    lc = lcm.LCM(lcm_url)
    reports: list = []
    lc.subscribe("SIM.LOCKSTEP", lambda _c, d: reports.append(lockstep_t.decode(d))).set_queue_capacity(1000)
    procs = [
        subprocess.Popen(
            [str(c) for c in cmd], env=child_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
        )
        for cmd in (mgr, nav)
    ]

    def pump(seconds: float, until) -> bool:
        end = time.monotonic() + seconds
        while time.monotonic() < end and not until():
            lc.handle_timeout(20)
        return until()

    def done(name: str, step: int) -> int:
        return sum(1 for m in reports if m.participant == name and m.kind == K.KIND_STEP_DONE and m.step == step)

    def clock(step: int) -> None:
        c = sim_clock_t()
        c.utime, c.server_id, c.mode, c.step, c.step_us = (
            step * 100_000,
            "test",
            sim_clock_t.MODE_LOCKSTEP,
            step,
            100_000,
        )
        lc.publish("SIM.CLOCK", c.encode())

    try:
        assert pump(
            60, lambda: {m.participant for m in reports if m.kind == K.KIND_REGISTER} >= {"AUV1.NAVIGATOR", "AUV1.NAV"}
        ), [p.poll() for p in procs]
        for step in range(3):
            clock(step)
            assert pump(30, lambda: done("AUV1.NAVIGATOR", step) >= 1)
            # the filter must not report before its simulator: keep handling
            # messages a while, failing as soon as its report shows up
            assert not pump(0.3, lambda: done("AUV1.NAV", step) > 0), "the filter reported before its simulator"
            lc.publish("SIM.LOCKSTEP", lockstep_msg("AUV1.sim", K.KIND_STEP_DONE, step, step * 100_000).encode())
            assert pump(30, lambda: done("AUV1.NAV", step) >= 1)
        # no clock for step 3 (as if lost): both repeat their report of step 2
        assert pump(30, lambda: done("AUV1.NAVIGATOR", 2) >= 3 and done("AUV1.NAV", 2) >= 3)
        assert done("AUV1.NAVIGATOR", 3) == 0
    finally:
        for p in procs:
            p.terminate()
        outs = [p.communicate(timeout=30)[0] for p in procs]
    for p, out in zip(procs, outs):
        assert p.returncode == 0, out

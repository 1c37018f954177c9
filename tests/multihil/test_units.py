"""The pure parts of multi-HIL: election rules, clock estimation and steering,
the lockstep bookkeeping, the environment service. No LCM, no processes."""

from __future__ import annotations

import random
import time

import pytest

from auv import env_election_t, env_needs_t, env_sample_t, lockstep_t
from sim.environment import CurrentLayer, Environment, EnvParams
from sim.multihil.clock import LocalClock, SteeredClock
from sim.multihil.clocksync import SyncEstimator
from sim.multihil.election import Election, Timing, rank
from sim.multihil.lockstep import LockstepTracker, Participation, decode_lockstep, lockstep_msg
from sim.multihil.server import LockstepServer, evaluate


def test_rank_orders_by_priority_then_smaller_id():
    assert rank(5, "B") > rank(3, "A")
    assert rank(3, "A") > rank(3, "B")  # tie: the smaller id wins
    assert rank(3, "AUV1") > rank(3, "AUV10")


class FakeWall:
    """The elections' wall clock, moved by the test: windows of 50 ms checked
    with real sleeps failed on a loaded machine (a sleep overshot a window)."""

    def __init__(self) -> None:
        self.t = 1000.0

    def __call__(self) -> float:
        return self.t

    def sleep(self, dt: float) -> None:
        self.t += dt


WALL = FakeWall()


def fast_election(my_id: str, prio: int) -> Election:
    return Election(
        my_id,
        prio,
        Timing(join_window_s=0.05, failover_timeout_s=0.05, election_wait_s=0.05, peer_timeout_s=5.0),
        clock=WALL,
    )


def test_the_best_candidate_wins_and_the_others_wait_for_it():
    a, b = fast_election("A", 1), fast_election("B", 9)
    a.heard("B", 9)
    b.heard("A", 1)
    WALL.sleep(0.06)
    assert a.poll() == "" and a.role == "client"
    assert b.poll() == "become_server" and b.server_term == 1


def test_a_silent_better_candidate_is_suspected_and_the_next_takes_over():
    a = fast_election("A", 1)
    a.heard("B", 9)  # B announced itself, then died
    WALL.sleep(0.06)
    assert a.poll() == ""  # waits for B first
    WALL.sleep(0.06)
    a.poll()  # B suspected
    assert a.poll() == "become_server"


def test_failover_goes_to_the_highest_live_priority_with_a_higher_term():
    c = fast_election("C", 5)
    c.heard("D", 2)
    assert c.on_heartbeat("S", term=3, priority=10) == "follow"
    assert c.server_id == "S"
    WALL.sleep(0.06)
    c.heard("D", 2)
    assert c.poll() == "lost"
    assert c.poll() == "become_server" and c.server_term == 4


def test_a_server_steps_down_for_a_higher_term_or_a_better_node_only():
    s = fast_election("S", 5)
    WALL.sleep(0.06)
    assert s.poll() == "become_server" and s.server_term == 1
    assert s.on_heartbeat("X", term=1, priority=4) == "ignore"  # same term, lower priority
    assert s.on_heartbeat("X", term=1, priority=5) == "ignore"  # same priority, "S" < "X"
    assert s.role == "server"
    assert s.on_heartbeat("Y", term=2, priority=0) == "step_down"  # higher term wins
    assert s.role == "client" and s.server_id == "Y"


def test_a_server_that_hands_over_is_replaced_by_the_best_node_at_once():
    """Lockstep before step 0 (node.py _hand_over): the first server yields to a
    better node it heard; its client takes over without a failover timeout."""
    first, best = fast_election("B", 0), fast_election("A", 0)  # "A" < "B": A is better
    WALL.sleep(0.06)
    assert first.poll() == "become_server" and first.server_term == 1
    assert best.on_heartbeat("B", term=1, priority=0) == "follow"
    first.heard("A", 0)
    assert first.best() == ("A", 0)
    first.hand_over()  # STEP_DOWN on the wire
    best.on_step_down("B")
    assert best.poll() == "become_server" and best.server_term == 1  # the same term: nothing served yet
    assert first.role == "client" and first.poll() == ""  # waits for A, never retakes
    assert first.on_heartbeat("A", term=1, priority=0) == "follow"
    other = fast_election("C", 0)
    assert other.on_heartbeat("A", term=1, priority=0) == "follow"
    other.on_step_down("B")  # not its server: nothing
    assert other.server_id == "A"


def test_clock_estimate_converges_under_offset_drift_and_asymmetric_delay():
    rng = random.Random(3)
    offset, drift = 12_345.0, 80e-6  # global = (1 + drift) * local + offset
    est = SyncEstimator()
    true_global = lambda loc: (1 + drift) * loc + offset  # noqa: E731
    loc = 1e6
    for _ in range(200):  # 10 Hz for 20 s
        loc += 1e5
        up, down = 100 + rng.expovariate(1 / 300), 100 + rng.expovariate(1 / 300)
        t1, t4 = loc, loc + up + 20 + down
        t2 = true_global(loc + up)
        est.add(t1, t2, t2 + 20 * (1 + drift), t4)
    err = est.global_at(loc) - true_global(loc)
    assert abs(err) < 50.0, err
    assert abs(est.drift_ppm - 80.0) < 5.0, est.drift_ppm


def test_impossible_exchanges_are_rejected():
    est = SyncEstimator()
    assert est.add(100.0, 50.0, 40.0, 200.0) is None  # t3 before t2
    assert est.add(100.0, 50.0, 60.0, 90.0) is None  # t4 before t1
    assert est.rejected == 2 and est.count == 0


def test_steered_clock_never_runs_backwards():
    local = LocalClock()
    clk = SteeredClock(local)
    clk.set(5e6)
    rng = random.Random(1)
    last = clk.now()
    for _ in range(2000):
        clk.steer(rng.uniform(-1e6, 1e6), 1.0 + rng.uniform(-1e-3, 1e-3))
        now = clk.now()
        assert now >= last
        last = now
    clk.set(0.0)  # a set behind the clock is refused
    assert clk.now() >= last


def test_the_fast_lockstep_decoder_agrees_with_the_generated_one_and_refuses_the_rest():
    rng = random.Random(3)
    for _ in range(200):
        name = "".join(rng.choice("AUV1.simNAVIGATORé") for _ in range(rng.randint(0, 30)))
        kind, step, utime = rng.choice((0, 1, 2)), rng.randint(-(2**63), 2**63 - 1), rng.randint(-(2**63), 2**63 - 1)
        data = lockstep_msg(name, kind, step, utime).encode()
        fast, slow = decode_lockstep(data), lockstep_t.decode(data)
        assert (fast.participant, fast.kind, fast.step, fast.utime) == (
            slow.participant,
            slow.kind,
            slow.step,
            slow.utime,
        )
    good = lockstep_msg("AUV1.sim", 1, 7, 350_000).encode()
    nul = 8 + 8 + 4 + len("AUV1.sim")  # fingerprint, utime, length, then the name
    bad = [
        b"",
        good[:-1],  # cut short
        good + b"\0",  # a byte more: another layout
        b"\0" * 8 + good[8:],  # another type's fingerprint
        good[:16] + (999).to_bytes(4, "big") + good[20:],  # a participant longer than the message
        good[:16] + (0).to_bytes(4, "big") + good[20:],  # no room for the NUL
        good[:nul] + b"X" + good[nul + 1 :],  # the participant's NUL overwritten
    ]
    for data in bad:
        with pytest.raises(ValueError):
            decode_lockstep(data)


def test_lockstep_waits_for_every_participant_and_drops_the_silent():
    tracker = LockstepTracker(timeout_s=0.05, log=lambda s: None)
    srv = LockstepServer(tracker, step_us=100_000, expect=2)
    tracker.on_message(lockstep_msg("AUV1.sim", lockstep_t.KIND_REGISTER, 0, 0))
    assert srv.poll() is None  # expects two participants
    tracker.on_message(lockstep_msg("AUV1.NAV", lockstep_t.KIND_REGISTER, 0, 0))
    assert srv.poll() == 0
    tracker.on_message(lockstep_msg("AUV1.sim", lockstep_t.KIND_STEP_DONE, 0, 0))
    assert srv.poll() is None  # AUV1.NAV has not finished step 0
    tracker.on_message(lockstep_msg("AUV1.NAV", lockstep_t.KIND_STEP_DONE, 0, 0))
    assert srv.poll() == 1 and srv.utime(1) == 100_000
    tracker.on_message(lockstep_msg("AUV1.sim", lockstep_t.KIND_STEP_DONE, 1, 100_000))
    time.sleep(0.06)
    assert srv.poll() == 2 and tracker.dropped == 1  # AUV1.NAV went silent: dropped


def test_participant_confirms_a_repeated_step_without_redoing_it():
    sent = []
    p = Participation("AUV1.sim", sent.append)
    p.on_clock(4, 400_000)
    p.done()
    p.on_clock(4, 400_000)  # a new server repeats step 4
    assert p.pending is None and [m.step for m in sent] == [4, 4]


def test_each_client_gets_only_what_it_asked_for_at_its_position():
    env = Environment(
        EnvParams(
            current=[CurrentLayer(0, 0.3, 0.1)],
            bathymetry_ref="slope:depth=40,dn=0.01,de=0",
            sound_speed_gradient_per_m=0.02,
        )
    )
    needs = env_needs_t()
    needs.utime, needs.client_id, needs.vehicle = 5_000_000, "AUV2-sim", "AUV2"
    needs.variables, needs.n_variables = ["bathymetry", "sound_speed"], 2
    needs.north_m, needs.east_m, needs.depth_m = 100.0, 0.0, 10.0
    s = evaluate(env, needs, term=3)
    assert s.valid_mask == env_sample_t.HAS_BATHYMETRY | env_sample_t.HAS_SOUND_SPEED
    assert abs(s.water_depth_m - 41.0) < 1e-9 and abs(s.sound_speed_mps - 1500.2) < 1e-9
    assert s.current_ned_mps == [0.0, 0.0, 0.0] and s.utime == 5_000_000 and s.term == 3


def memq_node(log: list, **kw):
    import lcm

    from sim.multihil.node import EnvNode, NodeConfig

    lc = lcm.LCM("memq://")
    return lc, EnvNode(NodeConfig("C-sim", "C", **kw), lc, Environment(EnvParams()), log=log.append)


def test_bad_traffic_is_counted_and_a_world_it_cannot_build_is_refused():
    log: list[str] = []
    lc, node = memq_node(log)
    lc.publish("SIM.ENV_HEARTBEAT", b"\x00" * 5)  # undecodable: counted, dropped
    lc.handle_timeout(100)
    assert node.rx.decode_errors == 1
    node.election.on_heartbeat("S-sim", 1, 5)  # follow a server ...
    world = Environment(EnvParams(bathymetry_ref="flat:depth=30")).to_env_model(0, "S-sim", 1)
    world.bathymetry_ref = "grid:no/such/bay.npz"  # ... whose grid this host lacks
    lc.publish("SIM.ENV", world.encode())
    lc.handle_timeout(100)
    assert node.env_adoptions == 0 and node.env.params.bathymetry_ref == "flat:depth=50"
    assert any("cannot build the server's world" in line for line in log), log
    world.bathymetry_ref = "flat:depth=30"  # one it can build: adopted in place
    lc.publish("SIM.ENV", world.encode())
    lc.handle_timeout(100)
    assert node.env_adoptions == 1 and node.env.water_depth(0.0, 0.0) == 30.0


def test_a_clock_of_another_mode_is_refused_with_a_message():
    from auv import sim_clock_t

    log: list[str] = []
    lc, node = memq_node(log, mode="lockstep")
    c = sim_clock_t()
    c.utime, c.server_id, c.term, c.mode, c.warp, c.step, c.step_us = 5, "S-sim", 1, 1, 4.0, 0, 0
    lc.publish("SIM.CLOCK", c.encode())
    lc.handle_timeout(100)
    assert node.last_clock is None and node.mode_conflicts == 1
    assert "every simulator of a world needs the same mode" in log[-1]


def test_a_server_stopped_after_its_loop_check_sends_nothing_more_of_its_term():
    """SIGSTOP can land anywhere, also after the loop's gap check and before a
    heartbeat or a clock goes out: on SIGCONT the server must not send them (the
    world has a newer term by then), whatever it was about to do."""
    log: list[str] = []
    lc, node = memq_node(log, mode="scaled")
    sent: list[str] = []
    for ch in ("SIM.ENV_HEARTBEAT", "SIM.CLOCK", "SIM.ENV_ELECTION"):
        lc.subscribe(ch, lambda c, _d: sent.append(c))
    deadline = time.monotonic() + 10.0
    while node.role != "server":  # alone: it serves after its join window
        assert time.monotonic() < deadline, log
        node.poll()
        lc.handle_timeout(20)
    while lc.handle_timeout(0) > 0:  # what it sent as it took the role
        pass
    assert "SIM.ENV_HEARTBEAT" in sent
    sent.clear()
    node.election.check_gap()  # the loop's check passed ...
    node.election.last_active -= 3.0  # ... then the process was stopped for 3 s
    node._heartbeat()
    node._publish_clock(10_000_000, 0)
    node._election_msg(env_election_t.KIND_ELECTED, node.term)
    while lc.handle_timeout(0) > 0:
        pass
    assert sent == [] and node.role == "reconfirming", (sent, node.role)
    node.poll()  # what it says of the gap
    assert any("stopped serving term" in line for line in log), log


def test_the_server_serves_the_ocean_and_a_client_adopts_it():
    """One world, one ocean: the server samples temperature and salinity (and the
    sound speed of that water) for a client that needs them, and a client whose
    own world has no ocean takes the server's from SIM.ENV, front, plumes and all."""
    from sim.ocean import Front, OceanParams, Plume

    ocean = OceanParams(front=Front(offset_m=50.0, amplitude_m=20.0, period_s=600.0), plumes=[Plume(10.0, 5.0, 4.0)])
    server_env = Environment(EnvParams(seed=9, current=[CurrentLayer(0, 0.2, 0.0)], ocean=ocean))
    needs = env_needs_t()
    needs.utime, needs.client_id, needs.vehicle = 30_000_000, "C-sim", "C"
    needs.variables, needs.n_variables = ["ocean", "sound_speed"], 2
    needs.north_m, needs.east_m, needs.depth_m = 12.0, 40.0, 4.0
    s = evaluate(server_env, needs, term=2)
    assert s.valid_mask == env_sample_t.HAS_OCEAN | env_sample_t.HAS_SOUND_SPEED
    assert (s.temperature_c, s.salinity_psu) == server_env.temperature_salinity(30.0, 12.0, 40.0, 4.0)
    assert s.sound_speed_mps == server_env.sound_speed(4.0, 30.0, 12.0, 40.0) and s.sound_speed_mps != 1500.0
    log: list[str] = []
    lc, node = memq_node(log)
    assert node.env.ocean is None
    node.election.on_heartbeat("S-sim", 2, 5)
    lc.publish("SIM.ENV", server_env.to_env_model(30_000_000, "S-sim", 2).encode())
    lc.handle_timeout(100)
    assert node.env_adoptions == 1 and node.env.params.ocean == ocean
    pts = [(t, n, 40.0, d) for t in (0.0, 30.0, 400.0) for n, d in ((12.0, 4.0), (-80.0, 30.0))]
    assert [node.env.temperature_salinity(*x) for x in pts] == [server_env.temperature_salinity(*x) for x in pts]
    node._on_sample("SIM.ENV_SAMPLE.C-sim", s)  # cross-checked against its own: no mismatch
    assert node.samples_received == 1 and node.sample_mismatches == 0

"""A node that was not running (SIGSTOP, a GC pause, a swapped-out VM) acts on
nothing it knew before until it re-confirmed it (issue 12, item 4). The
election's own rules, on a clock the test moves: deterministic."""

from __future__ import annotations

from sim.multihil.election import Election, Timing


class Wall:
    def __init__(self) -> None:
        self.t = 500.0

    def __call__(self) -> float:
        return self.t


def node(my_id: str, prio: int, wall: Wall) -> Election:
    return Election(
        my_id,
        prio,
        Timing(join_window_s=0.2, failover_timeout_s=0.5, election_wait_s=0.5, peer_timeout_s=2.5),
        clock=wall,
    )


def run(e: Election, wall: Wall, seconds: float, step: float = 0.05) -> list[str]:
    """The node's loop: check_gap() and poll() every step."""
    events = []
    end = wall.t + seconds
    while wall.t < end:
        wall.t += step
        e.check_gap()
        ev = e.poll()
        if ev:
            events.append(ev)
    return events


def server(wall: Wall) -> Election:
    s = node("A", 9, wall)
    assert run(s, wall, 0.3) == ["become_server"] and s.server_term == 1
    return s


def test_a_short_pause_changes_nothing():
    wall = Wall()
    s = server(wall)
    wall.t += 0.4  # under the failover timeout
    assert not s.check_gap() and s.poll() == "" and s.role == "server"


def test_a_paused_server_stops_serving_and_follows_the_one_that_took_over():
    wall = Wall()
    s = server(wall)
    wall.t += 3.0  # SIGSTOP 3 s, SIGCONT
    assert s.check_gap()
    assert s.role == "reconfirming" and s.gaps == 1 and abs(s.last_gap_s - 3.0) < 1e-9
    assert s.poll() == "paused"
    assert run(s, wall, 0.3) == [] and s.role == "reconfirming"  # listens, serves nothing
    assert s.on_heartbeat("B", term=2, priority=5) == "follow"
    assert s.role == "client" and s.server_id == "B" and s.server_term == 2
    wall.t += 0.1
    s.on_heartbeat("B", term=2, priority=5)
    s.check_gap()
    assert s.poll() == "" and s.role == "client" and s.server_id == "B"


def test_a_heartbeat_handled_before_the_first_poll_after_the_pause_is_followed():
    wall = Wall()
    s = server(wall)
    wall.t += 3.0
    # the loop resumes inside lc.handle(): the handler calls check_gap() first
    assert s.check_gap()
    assert s.on_heartbeat("B", term=2, priority=5) == "follow" and s.role == "client"
    assert s.poll() == "paused"  # reported once, then business as usual
    assert s.poll() == ""


def test_alone_after_a_pause_it_serves_again_only_after_the_window_and_in_a_new_term():
    wall = Wall()
    s = server(wall)
    wall.t += 3.0
    s.check_gap()
    assert s.poll() == "paused"
    t0 = wall.t
    events = []
    while not events:
        wall.t += 0.05
        s.check_gap()
        ev = s.poll()
        if ev:
            events.append(ev)
    assert events == ["become_server"]
    assert wall.t - t0 >= s.timing.reconfirm_s - 1e-9  # a full window with nobody serving
    assert s.server_term == 2  # the old term is never served again


def test_a_paused_client_does_not_declare_its_server_lost_before_listening():
    wall = Wall()
    c = node("C", 1, wall)
    c.check_gap()  # its loop ran
    assert c.on_heartbeat("S", term=4, priority=9) == "follow"
    wall.t += 3.0  # the client was frozen
    c.check_gap()
    assert c.poll() == "paused"
    wall.t += 0.1
    c.check_gap()
    assert c.poll() == "" and c.server_id == "S"  # not lost, not a candidate: listening
    c.on_heartbeat("S", term=4, priority=9)  # the server's queued heartbeats
    assert c.poll() == "" and c.server_id == "S"


def test_a_paused_client_claims_nothing_while_its_peers_look_dead():
    """After 3 s every peer looks silent (peer timeout 2.5 s): without the window
    the frozen client would make itself server at once, before it hears anyone."""
    wall = Wall()
    c = node("C", 9, wall)
    c.check_gap()
    c.heard("D", 1)
    c.on_heartbeat("S", term=1, priority=5)
    wall.t += 3.0
    c.check_gap()
    assert c.poll() == "paused"
    for _ in range(10):  # 0.5 s: the server speaks meanwhile
        wall.t += 0.05
        c.on_heartbeat("S", term=1, priority=5)
        c.check_gap()
        assert c.poll() == ""
    assert c.role == "client" and c.server_id == "S"


def test_a_resumed_server_node_sends_nothing_before_it_reconfirmed(monkeypatch):
    """The issue's path, in one process on a moved clock: the server's loop runs
    (poll) before it has read anything after a 3 s stop. It used to send one
    SIM.CLOCK 6 s of global time (x2) behind, in its old term; now it sends no
    heartbeat, clock or world until it follows whoever serves."""
    import time

    from auv import env_heartbeat_t, sim_clock_t
    from auvlcm.offline import OfflineLcm
    from sim.environment import Environment, EnvParams
    from sim.multihil.node import EnvNode, NodeConfig

    wall = Wall()
    monkeypatch.setattr(time, "monotonic", wall)
    monkeypatch.setattr(time, "monotonic_ns", lambda: int(wall() * 1e9))
    lc = OfflineLcm()
    node = EnvNode(
        NodeConfig("A-sim", "A", 9, mode="scaled", warp=2.0, timing=Timing(join_window_s=0.2)),
        lc,
        Environment(EnvParams()),
        log=lambda _line: None,
    )
    node.election.clock = wall
    node.election.decide_at = node.election.waiting_since = wall.t + 0.2
    for _ in range(50):  # 1 s: it serves term 1
        wall.t += 0.02
        node.poll()
    ticks = [sim_clock_t.decode(d) for ch, d in lc.published if ch == "SIM.CLOCK"]
    assert node.role == "server" and len(ticks) >= 15 and {c.term for c in ticks} == {1}
    wall.t += 3.0  # SIGSTOP 3 s, SIGCONT
    lc.published.clear()
    for _ in range(10):
        wall.t += 0.02
        node.poll()
    late = [sim_clock_t.decode(d) for ch, d in lc.published if ch == "SIM.CLOCK"]
    assert not late, [(c.utime - ticks[-1].utime, c.term) for c in late]
    assert not [ch for ch, _ in lc.published if ch in ("SIM.ENV_HEARTBEAT", "SIM.ENV")]
    assert node.role == "reconfirming"
    hb = env_heartbeat_t()
    hb.utime, hb.server_id, hb.priority, hb.term = ticks[-1].utime + 6_500_000, "B-sim", 1, 2
    sub = next(s for s in node.rx.subscriptions if s.channel == "SIM.ENV_HEARTBEAT")
    sub.on_raw("SIM.ENV_HEARTBEAT", hb.encode())
    assert node.role == "client" and node.election.server_id == "B-sim"
    for _ in range(10):
        wall.t += 0.02
        node.poll()
    assert not [ch for ch, _ in lc.published if ch == "SIM.CLOCK"]


def test_a_sync_reply_far_off_the_worlds_clock_cannot_set_a_clients_clock():
    """A forged or corrupt SIM.CLOCK_SYNC reply (right ids and seq, stamps in 2096)
    would set a joining client's global time; it is dropped (jump) and counted."""
    from auv import clock_sync_t, env_heartbeat_t, sim_clock_t
    from auvlcm.offline import OfflineLcm
    from sim.environment import Environment, EnvParams
    from sim.multihil.node import EnvNode, NodeConfig

    lc = OfflineLcm()
    node = EnvNode(NodeConfig("C-sim", "C", 1), lc, Environment(EnvParams()), log=lambda _line: None)

    def feed(channel, msg):
        next(s for s in node.rx.subscriptions if s.channel == channel).on_raw(channel, msg.encode())

    hb = env_heartbeat_t()
    hb.utime, hb.server_id, hb.priority, hb.term = 5_000_000, "S-sim", 9, 1
    feed("SIM.ENV_HEARTBEAT", hb)
    c = sim_clock_t()
    c.utime, c.server_id, c.term, c.warp = 5_000_000, "S-sim", 1, 1.0
    feed("SIM.CLOCK", c)
    for _ in range(8):
        node._next["sync"] = 0.0
        node.poll()  # a request goes out
        req = clock_sync_t.decode(next(d for ch, d in reversed(lc.published) if ch == "SIM.CLOCK_SYNC"))
        req.kind, req.server_id = clock_sync_t.KIND_REPLY, "S-sim"
        req.t2_server_recv_us = req.t3_server_send_us = 4_000_000_000_000_000
        feed("SIM.CLOCK_SYNC", req)
    assert node.sync.count == 0 and not node.clock.is_set and not node.joined
    assert node.drops.counts["jump"] == 8

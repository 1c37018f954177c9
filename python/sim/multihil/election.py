"""Who serves the world: join, elect, fail over, resolve two servers.

Pure decisions on wall time (time.monotonic), no LCM: node.py feeds it what
it hears and acts on what it decides, so the rules are testable alone.

- A node starts without a server and listens for `join_window_s`; hearing a
  heartbeat makes it a client of that server.
- Without a server it stands as a candidate (node.py sends env_election_t
  CANDIDATE). The best live node -- highest priority, ties to the smaller id
  -- becomes the server for term max_term + 1 once its window is over; the
  others wait for it and, if it never speaks, suspect it and go on with the
  next best.
- Missing heartbeats for `failover_timeout_s` loses the server. The best
  remaining node takes over at once (no window: every node already knows
  its peers' priorities from their announcements).
- A server that hears a better one -- higher term, then priority, then
  smaller id -- steps down and becomes its client.
- A node that was not running for longer than the failover timeout (SIGSTOP,
  a long GC pause, a swapped-out VM: check_gap(), called by the node at each
  turn of its loop and before each message it handles) acts on
  nothing it knew before: a server drops to "reconfirming" and serves no
  more, every node listens for a re-confirm window before it declares a
  server lost or claims the role. A re-confirming node follows the first
  server it hears; if nobody serves within the window it stands like any
  node, and a win gives it a new term: an old term is never served again.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field


@dataclass
class Peer:
    id: str
    priority: int | None = None
    last_heard: float = 0.0
    suspected_at: float | None = None  # suspected dead if not heard since


def rank(priority: int, node_id: str) -> tuple:
    """Sort key: larger is better (priority up, then the lexicographically smaller id)."""
    return (priority, tuple(-ord(c) for c in node_id) + (1,))  # 1: a prefix beats longer ids


@dataclass
class Timing:
    join_window_s: float = 1.0
    failover_timeout_s: float = 0.5
    election_wait_s: float = 0.5  # how long to wait for a better node to take over
    peer_timeout_s: float = 2.5  # a peer not heard for this long is not counted

    @property
    def reconfirm_s(self) -> float:
        """How long a node listens after a gap before it acts: a live server is heard
        within the failover timeout, a better candidate takes over within the wait."""
        return self.failover_timeout_s + self.election_wait_s


@dataclass
class Election:
    my_id: str
    my_priority: int
    timing: Timing = field(default_factory=Timing)
    role: str = "client"
    server_id: str = ""
    server_term: int = 0
    server_priority: int = 0
    max_term: int = 0
    last_heartbeat: float = 0.0
    peers: dict[str, Peer] = field(default_factory=dict)
    decide_at: float = 0.0  # earliest time to claim the role without a server
    waiting_since: float = 0.0
    elections_won: int = 0
    step_downs: int = 0
    gaps: int = 0  # times this node was not running for a failover timeout
    last_gap_s: float = 0.0
    reconfirm_until: float = 0.0  # after a gap: listen, decide nothing, until then
    last_active: float | None = None  # when check_gap() last saw this node running
    _paused: bool = False  # a gap not yet reported by poll()
    handed_term: int = 0  # term of a server that handed the world over (lockstep, before step 0)
    clock: Callable[[], float] = field(default=time.monotonic, repr=False)  # wall seconds; tests pass their own

    def __post_init__(self) -> None:
        now = self.clock()
        self.decide_at = now + self.timing.join_window_s
        self.waiting_since = self.decide_at

    # ------------------------------------------------------------ hearing
    def heard(self, node_id: str, priority: int | None = None) -> None:
        if node_id == self.my_id:
            return
        p = self.peers.setdefault(node_id, Peer(node_id))
        p.last_heard = self.clock()
        if priority is not None:
            p.priority = priority

    def on_heartbeat(self, server_id: str, term: int, priority: int) -> str:
        """A server's heartbeat; returns 'follow', 'step_down', or 'ignore'."""
        self.heard(server_id, priority)
        if server_id == self.my_id:
            return "ignore"
        self.max_term = max(self.max_term, term)
        theirs = (term, rank(priority, server_id))
        if self.role == "reconfirming":  # paused while serving: whoever serves now wins
            self.role = "client"
            self.step_downs += 1
            self._follow(server_id, term, priority)
            return "follow"
        if self.role == "server":
            if theirs > (self.server_term, rank(self.my_priority, self.my_id)):
                self.role = "client"
                self.step_downs += 1
                self._follow(server_id, term, priority)
                return "step_down"
            return "ignore"
        if (
            not self.server_id
            or server_id == self.server_id
            or theirs > (self.server_term, rank(self.server_priority, self.server_id))
            or self.clock() - self.last_heartbeat > self.timing.failover_timeout_s
        ):
            self._follow(server_id, term, priority)
            return "follow"
        return "ignore"

    def on_elected(self, node_id: str, term: int, priority: int) -> None:
        self.max_term = max(self.max_term, term)
        self.heard(node_id, priority)

    def on_step_down(self, node_id: str) -> None:
        """The server this node follows yields (it stops, or hands the world to a
        better node before a lockstep world's first step): no heartbeat will
        come, so the best remaining node takes over now, not after a timeout."""
        if self.role == "client" and node_id == self.server_id:
            self.handed_term = self.server_term  # the world has not begun: same term
            self.server_id = ""
            self.decide_at = self.waiting_since = self.clock()

    def hand_over(self) -> None:
        """A server yields to a better node it heard (lockstep, before step 0)."""
        self.role = "client"
        self.server_id = ""
        self.step_downs += 1
        self.decide_at = self.waiting_since = self.clock()

    def _follow(self, server_id: str, term: int, priority: int) -> None:
        self.server_id, self.server_term, self.server_priority = server_id, term, priority
        self.last_heartbeat = self.clock()

    # ----------------------------------------------------------- deciding
    def live_peers(self) -> list[Peer]:
        now = self.clock()
        return [
            p
            for p in self.peers.values()
            if p.priority is not None
            and now - p.last_heard <= self.timing.peer_timeout_s
            and (p.suspected_at is None or p.last_heard > p.suspected_at)
        ]

    def best(self) -> tuple[str, int]:
        cands = [(rank(p.priority, p.id), p.id, p.priority) for p in self.live_peers()]
        cands.append((rank(self.my_priority, self.my_id), self.my_id, self.my_priority))
        _, node_id, prio = max(cands)
        return node_id, prio

    def standing(self) -> bool:
        """True while there is no server: the node announces its candidacy."""
        return self.role != "server" and not self.server_id

    def check_gap(self) -> bool:
        """The node runs: called at each turn of its loop and before it handles a message.
        True when it was not running for longer than the failover timeout (see the module):
        it then acts on nothing it knew (a server stops serving) until it re-confirmed."""
        now = self.clock()
        last, self.last_active = self.last_active, now
        if last is None or now - last <= self.timing.failover_timeout_s:
            return False
        self._after_gap(now, now - last)
        return True

    def poll(self) -> str:
        """Time passes; returns 'lost' (server gone), 'become_server', 'paused' (check_gap()
        found a gap since the last poll), or ''."""
        now = self.clock()
        if self._paused:
            self._paused = False
            return "paused"
        if now < self.reconfirm_until:
            return ""
        if self.role == "reconfirming":  # nobody served in the window: stand like anyone
            self.role = "client"
        if self.role == "server":
            return ""
        if self.server_id and now - self.last_heartbeat > self.timing.failover_timeout_s:
            self._suspect(self.server_id, now)
            self.server_id = ""
            self.decide_at = self.waiting_since = now  # successors know each other: no window
            return "lost"
        if self.server_id or now < self.decide_at:
            return ""
        best_id, _ = self.best()
        if best_id == self.my_id:
            self.role = "server"
            # a hand-over before anything was served keeps its term (the same world
            # whatever the start order); any other win opens a new one
            term = self.max_term if self.handed_term == self.max_term > 0 else self.max_term + 1
            self.handed_term = 0
            self.server_id, self.server_term = self.my_id, term
            self.server_priority = self.my_priority
            self.max_term = self.server_term
            self.elections_won += 1
            return "become_server"
        if now - self.waiting_since > self.timing.election_wait_s:
            # the better node did not take over: count it out and go on
            self._suspect(best_id, now)
            self.waiting_since = now
        return ""

    def _after_gap(self, now: float, gap: float) -> None:
        self.gaps += 1
        self._paused = True
        self.last_gap_s = gap
        self.reconfirm_until = now + self.timing.reconfirm_s
        if self.role == "server":
            self.role = "reconfirming"
            self.server_id = ""
        elif self.server_id:
            self.last_heartbeat = now  # its silence during our gap proves nothing
        self.decide_at = self.waiting_since = self.reconfirm_until

    def _suspect(self, node_id: str, now: float) -> None:
        if node_id in self.peers:
            self.peers[node_id].suspected_at = now

    def resign(self) -> None:
        """Leave the server role (stopping): nothing to wait for any more."""
        self.role = "client"
        self.server_id = ""

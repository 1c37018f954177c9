"""The environment node inside every simulator: client, candidate or server.

One EnvNode per simulator process, on the process's LCM instance. poll() is
called from the process's loop; handlers run from lc.handle(). As a server it
publishes SIM.ENV_HEARTBEAT, SIM.CLOCK, SIM.ENV, answers SIM.CLOCK_SYNC and
serves SIM.ENV_SAMPLE.<client>; as a client it synchronises its clock,
announces its needs and adopts the server's environment. Control-plane
timers (heartbeats, failure detection, clock sync) run on wall time; what
reaches the vehicles (clock, environment, samples) runs on global time.

Time stamps it receives follow the project's rule (auvlcm.timepolicy): the
SIM.CLOCK it follows never runs backwards and refuses older terms; world
messages (SIM.ENV, samples) of an older term than its server's are dropped;
needs and sync replies with impossible stamps are dropped. Each drop is
counted per reason (`drops`) and logged the first time.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import lcm

from auv import (
    clock_offset_t,
    clock_sync_t,
    env_election_t,
    env_heartbeat_t,
    env_model_t,
    env_needs_t,
    env_sample_t,
    lockstep_t,
    sim_clock_t,
)
from auvlcm.rx import Receiver
from auvlcm.timepolicy import (
    FUTURE,
    INVALID,
    JUMP,
    MAX_CLOCK_JUMP_US,
    OLD_TERM,
    REGRESSION,
    ClockGate,
    InputGate,
    TimeDrops,
    valid_utime,
)
from sim import clock_modes
from sim.environment import Environment
from sim.multihil.clock import LocalClock, SteeredClock
from sim.multihil.clocksync import SyncEstimator
from sim.multihil.election import Election, Timing
from sim.multihil.lockstep import LockstepTracker
from sim.multihil.server import LockstepServer, evaluate


@dataclass
class NodeConfig:
    client_id: str
    vehicle: str
    priority: int = 0
    needs: list = field(default_factory=list)
    sample_rate_hz: float = 1.0
    mode: str = "realtime"  # realtime | scaled | lockstep
    warp: float = 1.0
    clock_rate_hz: float = 10.0  # SIM.CLOCK rate, free-running [Hz of global time]
    step_s: float = 0.1  # lockstep step
    lockstep_expect: int = 0  # participants to wait for before step 0
    lockstep_names: list = field(default_factory=list)  # ... and these, by name
    lockstep_timeout_s: float = 5.0
    heartbeat_hz: float = 10.0
    sync_hz: float = 10.0
    timing: Timing = field(default_factory=Timing)


class EnvNode:
    JOIN_SAMPLES = 5

    def __init__(
        self,
        cfg: NodeConfig,
        lc: lcm.LCM,
        env: Environment,
        local: LocalClock | None = None,
        position: Callable[[], tuple[float, float, float, float] | None] | None = None,
        on_env: Callable[[env_model_t], bool] | None = None,
        log=print,
        drops: TimeDrops | None = None,
        on_clock: Callable[[sim_clock_t], None] | None = None,
    ) -> None:
        self.cfg = cfg
        self.lc = lc
        self.env = env
        self.log = log
        self.local = local or LocalClock()
        self.clock = SteeredClock(self.local, cfg.warp if cfg.mode == "scaled" else 1.0)
        self.sync = SyncEstimator(self.clock.warp)
        self.position = position
        self.on_env = on_env
        self.on_clock = on_clock  # each SIM.CLOCK accepted (the lockstep simulator follows it)
        self.election = Election(cfg.client_id, cfg.priority, cfg.timing)
        self.tracker = LockstepTracker(cfg.lockstep_timeout_s, log)
        self.stepper = LockstepServer(
            self.tracker, int(round(cfg.step_s * 1e6)), cfg.lockstep_expect, log, expect_names=set(cfg.lockstep_names)
        )
        self.lockstep = cfg.mode == "lockstep"
        self.joined = False  # has a global time (as client or server)
        self.vehicles: dict[str, str] = {}  # client id -> vehicle, from announcements
        self.clients: dict[str, float] = {}  # client id -> wall time last heard (server)
        self.last_clock: sim_clock_t | None = None  # the newest SIM.CLOCK accepted
        self.drops = drops or TimeDrops(f"multihil: {cfg.client_id}", log)
        self.clock_gate = ClockGate(self.drops)
        self._needs_gates: dict[str, InputGate] = {}
        self.clock_messages = 0  # accepted ones
        self.samples_received = 0
        self.sample_mismatches = 0
        self.env_adoptions = 0
        self.mode_conflicts = 0
        self._seq = 0
        self._pending_sync: dict[int, float] = {}
        now = time.monotonic()
        self._next = {"candidate": now, "heartbeat": now, "sync": now, "offset": now + 1.0}
        self._next_tick_us = 0.0  # free-running SIM.CLOCK
        self._next_env_us = 0.0
        self._next_needs_t: float | None = None
        self.rx = Receiver(lc)
        sub = self.rx.subscribe
        sub("SIM.ENV_HEARTBEAT", env_heartbeat_t, self._on_heartbeat, 100)
        sub("SIM.ENV_ELECTION", env_election_t, self._on_election, 100)
        sub("SIM.CLOCK", sim_clock_t, self._on_clock, 1000)
        sub("SIM.CLOCK_SYNC", clock_sync_t, self._on_sync, 1000)
        sub("SIM.ENV", env_model_t, self._on_env_model, 10)
        sub("SIM.ENV_NEEDS", env_needs_t, self._on_needs, 1000)
        sub("SIM.LOCKSTEP", lockstep_t, self._on_lockstep, 1000)
        sub(f"SIM.ENV_SAMPLE.{cfg.client_id}", env_sample_t, self._on_sample, 100)

    # ------------------------------------------------------------ queries
    @property
    def clock_regressions(self) -> int:
        """SIM.CLOCK values refused because they were behind the clock or of an older term."""
        return self.drops.counts[REGRESSION] + self.drops.counts[OLD_TERM]

    @property
    def role(self) -> str:
        return self.election.role

    @property
    def term(self) -> int:
        return self.election.server_term

    def global_now_us(self) -> float | None:
        """This process's best global time, or None before it has one."""
        if self.lockstep:
            return float(self.last_clock.utime) if self.last_clock else None
        return self.clock.now() if self.joined else None

    def _publish(self, channel: str, msg) -> None:
        self.lc.publish(channel, msg.encode())

    def _publish_served(self, channel: str, msg) -> None:
        """What only the server sends (heartbeat, clock, the world), asked again
        just before it goes: a process can be stopped anywhere, also after the
        loop's own gap check, and a server resumed there would otherwise send one
        more message of its old term after another node took a newer one."""
        if self.election.check_gap() or self.role != "server":
            return
        self._publish(channel, msg)

    # ------------------------------------------------------------ polling
    def poll(self) -> None:
        now = time.monotonic()
        self.election.check_gap()
        event = self.election.poll()
        if event == "lost":
            self.log(
                f"multihil: {self.cfg.client_id}: lost server (no heartbeat for "
                f"{self.cfg.timing.failover_timeout_s:g} s)"
            )
        elif event == "become_server":
            self._take_over()
        elif event == "paused":
            was = self.stepper.started
            self.stepper.started = False
            self.log(
                f"multihil: {self.cfg.client_id}: not running for "
                f"{self.election.last_gap_s:.2f} s (more than the failover timeout): "
                + (f"stopped serving term {self.term}; " if self.role == "reconfirming" else "")
                + f"listening {self.cfg.timing.reconfirm_s:g} s before acting"
                + (" (lockstep paused)" if was else "")
            )
        # Before a lockstep world's first step the role is still open: every node
        # announces its priority, so the server can yield to the best one
        # (_hand_over): who serves does not depend on who started first.
        open_role = self.lockstep and self.last_clock is None and self.role != "server"
        if (self.election.standing() or open_role) and now >= self._next["candidate"]:
            self._next["candidate"] = now + 0.1
            self._election_msg(env_election_t.KIND_CANDIDATE, self.election.max_term + 1)
        if self.role == "server":
            self._serve(now)
        elif self.election.server_id:
            self._client(now)
        self._announce()

    def _serve(self, now: float) -> None:
        if now >= self._next["heartbeat"]:
            self._next["heartbeat"] = now + 1.0 / self.cfg.heartbeat_hz
            self._heartbeat()
        if self.lockstep:
            if not self.stepper.started and self.last_clock is None:
                best, prio = self.election.best()
                if best != self.cfg.client_id:
                    self._hand_over(best, prio)
                    return
            step = self.stepper.poll()
            if step is not None:
                self._publish_clock(self.stepper.utime(step), step)
        else:
            g = self.clock.now()
            if g >= self._next_tick_us:
                # the newest tick due (a late loop skips ticks, never sends an old one)
                period = 1e6 / self.cfg.clock_rate_hz
                tick = self._next_tick_us + period * int((g - self._next_tick_us) // period)
                self._next_tick_us = tick + period
                if self.clock_gate.now is None or tick >= self.clock_gate.now:
                    self._publish_clock(int(tick), 0)
        g = self.global_now_us()
        if g is not None and g >= self._next_env_us:
            self._next_env_us = g + 1e6
            self._publish_served("SIM.ENV", self.env.to_env_model(int(g), self.cfg.client_id, self.term))

    def _client(self, now: float) -> None:
        if now >= self._next["sync"]:
            self._next["sync"] = now + 1.0 / self.cfg.sync_hz
            self._seq += 1
            req = clock_sync_t()
            req.client_id, req.server_id, req.seq, req.kind = (
                self.cfg.client_id,
                "",
                self._seq,
                clock_sync_t.KIND_REQUEST,
            )
            t1 = self.local.now_us()
            req.utime = int(self.clock.now()) if self.clock.is_set else 0
            req.t1_client_send_us, req.t2_server_recv_us, req.t3_server_send_us = int(t1), 0, 0
            self._pending_sync = {k: v for k, v in self._pending_sync.items() if k > self._seq - 8}
            self._pending_sync[self._seq] = t1
            self._publish("SIM.CLOCK_SYNC", req)
        if not self.lockstep and self.joined and now >= self._next["offset"]:
            self._next["offset"] = now + 1.0
            self._publish(f"SIM.CLOCK_OFFSET.{self.cfg.client_id}", self.offset_msg())

    def offset_msg(self) -> clock_offset_t:
        m = clock_offset_t()
        loc = self.local.now_us()
        m.utime, m.client_id = int(self.clock.at(loc)), self.cfg.client_id
        m.offset_us = self.clock.at(loc) - loc
        m.drift_ppm = -self.sync.drift_ppm  # how fast the local clock runs against global
        m.round_trip_us = self.sync.best_delay_us
        m.samples = self.sync.count
        m.synchronised = self.sync.count >= 3 and abs(self.sync.global_at(loc) - self.clock.at(loc)) < 1000.0
        return m

    def _announce(self) -> None:
        """env_needs_t, paced by the vehicle's own sim time (deterministic in lockstep)."""
        if not self.joined or self.position is None:
            return
        pos = self.position()
        if pos is None:
            return
        t, n, e, d = pos
        if self._next_needs_t is not None and t < self._next_needs_t - 1e-9:
            return
        period = 1.0 / self.cfg.sample_rate_hz
        self._next_needs_t = (t if self._next_needs_t is None else self._next_needs_t) + period
        m = env_needs_t()
        m.utime, m.client_id, m.vehicle, m.priority = (
            int(round(t * 1e6)),
            self.cfg.client_id,
            self.cfg.vehicle,
            self.cfg.priority,
        )
        m.variables = list(self.cfg.needs)
        m.n_variables = len(m.variables)
        m.north_m, m.east_m, m.depth_m = n, e, d
        m.sample_rate_hz = self.cfg.sample_rate_hz
        self._publish("SIM.ENV_NEEDS", m)

    # ------------------------------------------------------ role changes
    def _take_over(self) -> None:
        el = self.election
        last = self.last_clock
        if self.lockstep:
            if last is not None and last.mode == sim_clock_t.MODE_LOCKSTEP:
                gone = self.vehicles.get(last.server_id)
                if gone and last.server_id != self.cfg.client_id:
                    self.tracker.remove(f"{gone}.sim")
                self.stepper.resume(last.step, last.utime)
                self._publish_clock(last.utime, last.step)
        else:
            floor = float(last.utime) if last is not None else 0.0
            if not self.clock.is_set:
                self.clock.set(floor)
            elif self.clock.now() < floor:
                self.clock.set(floor)  # forward only: never behind what the world saw
            self.clock.freeze()
            period = 1e6 / self.cfg.clock_rate_hz
            self._next_tick_us = (int(self.clock.now() // period) + 1) * period
        self.joined = True
        self._next_env_us = 0.0
        self.clock_gate.raise_term(el.server_term)  # its own clocks: a term it knows began
        g = self.global_now_us()
        self.log(
            f"multihil: {self.cfg.client_id}: server for term {el.server_term} "
            f"(priority {self.cfg.priority}) at global "
            f"{(g or 0) / 1e6:.3f} s"
        )
        self._election_msg(env_election_t.KIND_ELECTED, el.server_term)
        self._heartbeat()
        self._next["heartbeat"] = time.monotonic() + 1.0 / self.cfg.heartbeat_hz

    def _hand_over(self, best: str, priority: int) -> None:
        """Lockstep, before step 0: yield to the best node heard (priority, then the
        smaller id), which takes over at once, so the server is the same whatever
        the start order."""
        self.log(
            f"multihil: {self.cfg.client_id}: handing the world to {best} (priority {priority}) before the first step"
        )
        self._election_msg(env_election_t.KIND_STEP_DOWN, self.term)
        self.election.hand_over()

    def stop(self) -> None:
        """Leaving: a server says so, so that the others need not wait for the timeout."""
        if self.role == "server":
            self._election_msg(env_election_t.KIND_STEP_DOWN, self.term)
            self.election.resign()

    # ---------------------------------------------------------- messages
    def _election_msg(self, kind: int, term: int) -> None:
        m = env_election_t()
        g = self.global_now_us()
        m.utime = int(g) if g is not None else 0
        m.candidate_id, m.priority, m.term, m.kind = self.cfg.client_id, self.cfg.priority, term, kind
        m.last_global_utime = self.last_clock.utime if self.last_clock else 0
        if kind == env_election_t.KIND_ELECTED:  # claims the role: only while it holds
            self._publish_served("SIM.ENV_ELECTION", m)
        else:
            self._publish("SIM.ENV_ELECTION", m)

    def _heartbeat(self) -> None:
        m = env_heartbeat_t()
        g = self.global_now_us()
        m.utime = int(g) if g is not None else 0
        m.server_id, m.priority, m.term = self.cfg.client_id, self.cfg.priority, self.term
        m.step = self.stepper.step if self.lockstep else 0
        now = time.monotonic()
        m.clients = sorted(c for c, t in self.clients.items() if now - t <= self.cfg.timing.peer_timeout_s)
        m.n_clients = len(m.clients)
        self._publish_served("SIM.ENV_HEARTBEAT", m)

    def _publish_clock(self, utime: int, step: int) -> None:
        c = sim_clock_t()
        c.utime, c.server_id, c.term = int(utime), self.cfg.client_id, self.term
        c.mode = clock_modes.WIRE[self.cfg.mode]
        c.warp = self.clock.warp if self.cfg.mode == "scaled" else 1.0
        c.step, c.step_us = step, self.stepper.step_us if self.lockstep else 0
        self._publish_served("SIM.CLOCK", c)

    # ---------------------------------------------------------- handlers
    def _on_heartbeat(self, _ch: str, m: env_heartbeat_t) -> None:
        self.election.check_gap()  # a message after a pause: re-confirm first
        if m.server_id == self.cfg.client_id:
            return
        before = self.election.server_id
        action = self.election.on_heartbeat(m.server_id, m.term, m.priority)
        if action in ("follow", "step_down"):
            self.clock_gate.raise_term(m.term)  # its clock is the world's: older terms are over
        if action == "step_down":
            self.log(
                f"multihil: {self.cfg.client_id}: stepping down for {m.server_id} "
                f"(term {m.term}, priority {m.priority})"
            )
            self._election_msg(env_election_t.KIND_STEP_DOWN, m.term)
            self.stepper.started = False
        if action in ("follow", "step_down") and before != m.server_id:
            self.sync.reset()
            self._pending_sync.clear()
            self._next["sync"] = time.monotonic()
            self.log(f"multihil: {self.cfg.client_id}: client of {m.server_id} (term {m.term})")

    def _on_election(self, _ch: str, m: env_election_t) -> None:
        self.election.check_gap()
        if m.candidate_id == self.cfg.client_id:
            return
        if m.kind == env_election_t.KIND_ELECTED:
            self.election.on_elected(m.candidate_id, m.term, m.priority)
        else:
            self.election.heard(m.candidate_id, m.priority)
        if m.kind == env_election_t.KIND_STEP_DOWN and self.lockstep and self.last_clock is None:
            self.election.on_step_down(m.candidate_id)  # a hand-over before step 0
        if m.kind == env_election_t.KIND_CANDIDATE and self.role == "server":
            self._heartbeat()  # someone lost us: be heard at once

    def _on_clock(self, _ch: str, m: sim_clock_t) -> None:
        self.election.check_gap()
        if (m.mode == sim_clock_t.MODE_LOCKSTEP) != self.lockstep:
            self.mode_conflicts += 1
            if self.mode_conflicts == 1:
                self.log(
                    f"multihil: {self.cfg.client_id}: SIM.CLOCK from {m.server_id} is "
                    f"{'lockstep' if m.mode == sim_clock_t.MODE_LOCKSTEP else 'free-running'}, but this simulator "
                    f"runs {self.cfg.mode}: every simulator of a world needs the same mode"
                )
            return
        if not self.clock_gate.offer(m.utime, m.term):
            return
        self.clock_messages += 1
        self.last_clock = m
        if self.lockstep and self.role != "server":
            self.joined = True
        if self.on_clock is not None:
            self.on_clock(m)

    def _on_sync(self, _ch: str, m: clock_sync_t) -> None:
        self.election.check_gap()
        if m.kind == clock_sync_t.KIND_REQUEST:
            self.election.heard(m.client_id)
            t2 = self.global_now_us()
            if self.role == "server" and t2 is not None:  # lockstep: none before step 0
                self.clients[m.client_id] = time.monotonic()
                m.kind, m.server_id = clock_sync_t.KIND_REPLY, self.cfg.client_id
                m.t2_server_recv_us = int(t2)
                m.t3_server_send_us = int(self.global_now_us())
                m.utime = m.t3_server_send_us
                self._publish("SIM.CLOCK_SYNC", m)
            return
        if m.client_id != self.cfg.client_id or m.server_id != self.election.server_id:
            return
        if not (valid_utime(m.t2_server_recv_us) and valid_utime(m.t3_server_send_us)):
            self.drops.drop(
                INVALID,
                "SIM.CLOCK_SYNC",
                f"reply stamps {m.t2_server_recv_us}, {m.t3_server_send_us} outside the valid range",
            )
            return
        ref = self.clock_gate.now  # the world's clock: a reply far off it cannot be its server's
        if ref is not None and abs(m.t3_server_send_us - ref) > MAX_CLOCK_JUMP_US:
            self.drops.drop(JUMP, "SIM.CLOCK_SYNC", f"reply at {m.t3_server_send_us}, the world's clock is at {ref}")
            return
        t1 = self._pending_sync.pop(m.seq, None)
        if t1 is None or self.lockstep:
            return
        t4 = self.local.now_us()
        if self.sync.add(t1, m.t2_server_recv_us, m.t3_server_send_us, t4) is None:
            return
        target = self.sync.global_at(t4)
        if not self.clock.is_set:
            if self.sync.count < self.JOIN_SAMPLES:
                return  # set the clock from the best of a few, not the first one
            self.clock.set(target, t4)
        else:
            self.clock.steer(target - self.clock.at(t4), self.clock.warp + self.sync.drift)
        if not self.joined:
            self.joined = True
            self.log(f"multihil: {self.cfg.client_id}: joined at global {target / 1e6:.3f} s")

    def _on_env_model(self, _ch: str, m: env_model_t) -> None:
        self.election.check_gap()
        if m.server_id != self.election.server_id or self.role == "server":
            return
        if not self._current_term(m.term, m.utime, "SIM.ENV"):
            return
        params = Environment.params_from_env_model(m)
        if params == self.env.params:
            return
        if self.on_env is not None:
            if not self.on_env(m):  # the simulator rebuilds its world (sim.multihil.hook)
                return
        else:
            try:
                fresh = Environment(params, None)
            except (ValueError, OSError) as exc:  # e.g. a grid file this host lacks
                self.log(f"multihil: {self.cfg.client_id}: cannot build the server's world ({exc}); keeping this one")
                return
            self.env.replace_with(fresh)
        self.env_adoptions += 1
        self.log(f"multihil: {self.cfg.client_id}: adopted world {m.world!r} (seed {m.seed}) from {m.server_id}")

    def _current_term(self, term: int, utime: int, what: str) -> bool:
        """A world message of the server this node follows, in its term, with a valid stamp."""
        if not valid_utime(utime):
            self.drops.drop(INVALID, what, f"utime {utime} outside the valid range")
            return False
        if term < self.election.server_term:
            self.drops.drop(OLD_TERM, what, f"term {term} after term {self.election.server_term}")
            return False
        return True

    def _on_needs(self, _ch: str, m: env_needs_t) -> None:
        self.election.check_gap()
        self.vehicles[m.client_id] = m.vehicle
        self.election.heard(m.client_id, m.priority)
        if self.role != "server":
            return
        gate = self._needs_gates.get(m.client_id)
        if gate is None:
            gate = self._needs_gates[m.client_id] = InputGate(self.drops, f"SIM.ENV_NEEDS from {m.client_id}")
        if not gate.offer(m.utime, self.global_now_us()):
            return  # evaluated at its stamp: the world at 10^18 s is nobody's business
        self.clients[m.client_id] = time.monotonic()
        self._publish(f"SIM.ENV_SAMPLE.{m.client_id}", evaluate(self.env, m, self.term))

    def _on_sample(self, _ch: str, s: env_sample_t) -> None:
        self.election.check_gap()
        if not self._current_term(s.term, s.utime, f"SIM.ENV_SAMPLE.{self.cfg.client_id}"):
            return
        self.samples_received += 1
        t = s.utime / 1e6
        if (
            s.valid_mask & env_sample_t.HAS_BATHYMETRY
            and abs(s.water_depth_m - self.env.water_depth(s.north_m, s.east_m)) > 1e-6
        ):
            self.sample_mismatches += 1
        if s.valid_mask & env_sample_t.HAS_CURRENT:
            mine = self.env.current(t, s.north_m, s.east_m, s.depth_m)
            if max(abs(a - b) for a, b in zip(mine, s.current_ned_mps)) > 1e-6:
                self.sample_mismatches += 1
        if s.valid_mask & env_sample_t.HAS_OCEAN:
            temp, salt = self.env.temperature_salinity(t, s.north_m, s.east_m, s.depth_m)
            if abs(temp - s.temperature_c) > 1e-6 or abs(salt - s.salinity_psu) > 1e-6:
                self.sample_mismatches += 1

    def _on_lockstep(self, _ch: str, m: lockstep_t) -> None:
        self.election.check_gap()
        if m.kind == lockstep_t.KIND_STEP_DONE:
            known = max(
                self.last_clock.step if self.last_clock else -1, self.stepper.step if self.role == "server" else -1
            )
            if not 0 <= m.step <= known + 1:  # done with a step nobody published: a lie
                # (+ 1: the participant's report may overtake the clock across a relay)
                self.drops.drop(
                    FUTURE, "SIM.LOCKSTEP", f"{m.participant} done with step {m.step}, the newest published is {known}"
                )
                return
        self.tracker.on_message(m)

"""What the launcher knows about a running world, from LCM alone.

- ready: every simulator (ACTUATOR_STATE), every onboard navigation filter
  (NAV_STATUS, vehicles with `nav: ekf`), every auv-frontseat (FRONTSEAT,
  vehicles flown from their backseat) and every manager (CHASM status) of
  the scenario has reported, on any host: a filter that subscribes after the
  clock starts misses the first GPS fix and aligns a second later, so the
  mission would not be the same from run to run;
- the clock needs nothing from the watch: the launcher's clock is a lockstep
  server (tools/launch/worldclock.py), so no process falls behind it, whatever the
  load, and no lost report can hold it for ever;
- outcome: each vehicle's end manager (NAVIGATOR by default) is done,
  aborted or failed. A plan whose `abort when` rule fired and then ended
  normally (the surfacing state completed) counts as aborted: the plan's abort
  targets are read from its text. In a lockstep world the launcher asks for
  the outcome as of a step (outcome(before_us)): only ends stamped before that
  step's time count, all of which reached it before that step's clock, so the
  step the mission ends at is the same in every run (docs/scenarios.md, "End").

Stamps follow the project's rule (auvlcm.timepolicy): the SIM.CLOCK the watch
follows never goes back or jumps unconfirmed (one message at INT64_MAX cannot
end a mission on its time limit), and a report stamped outside the valid
range, from the future of that clock, or older than the last one from the
same process is dropped. Drops are
counted per reason in the launcher's summary and logged the first time.
"""

from __future__ import annotations

import re
import select
from collections.abc import Iterable
from dataclasses import dataclass, field

import lcm

from auv import actuator_state_t, chasm_status_t, frontseat_status_t, nav_filter_status_t, sim_clock_t
from auvlcm.rx import Receiver
from auvlcm.timepolicy import ClockGate, InputGate, TimeDrops
from tools.launch.annotate import plan_files
from tools.scenario.scenario_file import Scenario

_ABORT = re.compile(r"^\s*abort\s+when\b.*->\s*(?:resume\s+(?:deep\s+)?)?([A-Za-z_][\w/]*)", re.M)
FINAL = {chasm_status_t.RUN_DONE: "done", chasm_status_t.RUN_ABORTED: "aborted", chasm_status_t.RUN_FAILED: "failed"}


def abort_targets(plan) -> set[str]:
    """Names of the states `abort when` rules lead to, in a plan and its includes."""
    out: set[str] = set()
    for p in plan_files(plan):
        out |= {t.rsplit("/", 1)[-1] for t in _ABORT.findall(p.read_text())}
    return out


_PARAM = re.compile(r"^\s*param\s+([A-Za-z_]\w*)\s*=\s*(.*?)\s*(?:#.*)?$", re.M)


def plan_params(plan, overrides: dict[str, str]) -> dict[str, str]:
    """The plan's `param` values (its defaults, then the scenario's -D overrides)."""
    out: dict[str, str] = {}
    for p in plan_files(plan):
        out.update(_PARAM.findall(p.read_text()))
    return {**out, **{k: str(v) for k, v in overrides.items()}}


def expand(text: str, params: dict[str, str]) -> str:
    """`elapsed > $abort_at` as the plan ran it: `elapsed > 2 s`."""
    return re.sub(r"\$([A-Za-z_]\w*)", lambda m: params.get(m.group(1), m.group(0)), text)


def fired(status) -> str:
    """What ended a mission early, from the status of the transition: the tests
    named in its condition that were true (`nav_stale`, `leak, too_deep`), or
    the condition's text when none of its terms is a named test."""
    names = [n for n, val in zip(status.test_name, status.test_value) if val]
    return ", ".join(names) or status.last_condition


@dataclass
class VehicleState:
    end_manager: str
    abort_states: set
    path: str = ""
    condition: str = ""
    run_state: int = -1
    entered_abort: bool = False
    sim_us: int | None = None
    params: dict = field(default_factory=dict)  # the end manager's plan parameters
    cause: str = ""  # why the mission ended early: the tests that fired
    abort_condition: str = ""  # the whole condition of that transition
    abort_at_s: float | None = None
    lost_at_s: float | None = None  # lost by a planned fault (tools/scenario/faults.py)
    end_us: int | None = None  # sim time of the status that ended its plan, or of its loss

    @property
    def outcome(self) -> str | None:
        if self.lost_at_s is not None:
            return "lost"
        o = FINAL.get(self.run_state)
        return "aborted" if o == "done" and self.entered_abort else o


class MissionWatch:
    def __init__(self, lc: lcm.LCM, sc: Scenario, backseat: Iterable[str] = ()) -> None:
        """backseat: the vehicles flown from their backseat (tools/launch/backseat.py)."""
        self.lc = lc
        self.rx = Receiver(lc)
        self.time_drops = TimeDrops("launch", lambda line: print(line, flush=True))
        self.clock = ClockGate(self.time_drops)
        self._gates: dict[str, InputGate] = {}
        self.vehicles: dict[str, VehicleState] = {}
        self.seen: set[str] = set()
        self.expected: set[str] = set()
        self.sim_time_us = 0
        # The other managers' status only says they run: once seen, the
        # watch stops waking for it (each is a message per cycle). By channel.
        self._until_seen: dict = {}
        for v in sc.vehicles:
            end = next(m for m in v.managers if m.name == v.end_manager)
            self.vehicles[v.id] = VehicleState(
                v.end_manager, abort_targets(end.plan), params=plan_params(end.plan, end.params)
            )
            self.expected.add(f"{v.id}.sim")
            self.rx.subscribe(f"{v.id}.ACTUATOR_STATE", actuator_state_t, self._on_sim, queue_capacity=1000)
            if v.nav.source == "ekf":
                self.expected.add(f"{v.id}.NAV")
                self.rx.subscribe(f"{v.id}.NAV_STATUS", nav_filter_status_t, self._on_nav_status, queue_capacity=100)
            for m in v.managers:
                self.expected.add(f"{v.id}.{m.name}")
                sub = self.rx.subscribe(f"{v.id}.CHASM.{m.name}", chasm_status_t, self._on_status, queue_capacity=1000)
                if m.name != v.end_manager:
                    self._until_seen[sub.channel] = sub
        for vid in backseat:  # auv-frontseat: ready at its first state, then no longer heard
            self.expected.add(f"{vid}.FRONTSEAT")
            sub = self.rx.subscribe(f"{vid}.FRONTSEAT", frontseat_status_t, self._on_frontseat, queue_capacity=100)
            self._until_seen[sub.channel] = sub
        self.rx.subscribe("SIM.CLOCK", sim_clock_t, self._on_clock, queue_capacity=1000)

    def _fresh(self, channel: str, utime: int) -> bool:
        """The stamp of a report on channel passes the time rule (against the watch's clock)."""
        gate = self._gates.get(channel)
        if gate is None:
            gate = self._gates[channel] = InputGate(self.time_drops, channel)
        return gate.offer(utime, self.clock.now)

    def _on_sim(self, ch: str, m) -> None:
        if not self._fresh(ch, m.utime):
            return
        self.seen.add(f"{m.vehicle}.sim")
        v = self.vehicles.get(m.vehicle)
        if v is not None:
            v.sim_us = m.utime

    def _on_nav_status(self, ch: str, m) -> None:
        if not self._fresh(ch, m.utime):
            return
        self.seen.add(f"{m.vehicle}.NAV")

    def _on_frontseat(self, ch: str, m) -> None:
        if not self._fresh(ch, m.utime) or ch != f"{m.vehicle}.FRONTSEAT":
            return
        self.seen.add(ch)
        sub = self._until_seen.pop(ch, None)
        if sub is not None:
            self.rx.unsubscribe(sub)

    def _on_status(self, ch: str, m) -> None:
        if not self._fresh(ch, m.utime):
            return
        name = f"{m.vehicle}.{m.manager}"
        self.seen.add(name)
        v = self.vehicles.get(m.vehicle)
        if v is None or m.manager != v.end_manager:
            # only the manager's own report on its own channel ends the wait
            sub = self._until_seen.pop(ch, None) if ch == f"{m.vehicle}.CHASM.{m.manager}" else None
            if sub is not None:
                self.rx.unsubscribe(sub)
            return
        v.run_state = m.run_state
        if v.end_us is None and m.run_state in FINAL:
            v.end_us = m.utime
        if m.path_len:
            v.path = "/".join(m.active_path)
            if not v.entered_abort and any(s in v.abort_states for s in m.active_path):
                v.entered_abort = True
                v.cause, v.abort_condition = expand(fired(m), v.params), expand(m.last_condition, v.params)
                v.abort_at_s = m.last_transition_utime / 1e6
        if m.run_state in (chasm_status_t.RUN_ABORTED, chasm_status_t.RUN_FAILED) and not v.cause:
            v.cause = expand(fired(m), v.params) or FINAL[m.run_state]
            v.abort_condition = expand(m.last_condition, v.params)
            v.abort_at_s = m.utime / 1e6
        v.condition = m.last_condition

    def _on_clock(self, _ch: str, m) -> None:
        if self.clock.offer(m.utime, m.term):
            self.sim_time_us = m.utime

    def dropped(self) -> dict:
        """What the watch counted and dropped: undecodable messages, stamps per reason."""
        return {"decode_errors": self.rx.decode_errors, "time": {r: n for r, n in self.time_drops.counts.items() if n}}

    def handle(self, timeout_s: float) -> None:
        """Handle every message that is waiting, waiting up to timeout_s for the first."""
        handle_all = getattr(self.lc, "handle_all", None)
        if handle_all is not None:  # reads what is queued in batches (auvlcm/own_socket.py)
            handle_all(round(timeout_s * 1000))
            return
        fd = self.lc.fileno()
        ready, _, _ = select.select([fd], [], [], timeout_s)
        while ready:
            self.lc.handle()
            ready, _, _ = select.select([fd], [], [], 0.0)

    def all_ready(self) -> bool:
        return not self.expected - self.seen

    def not_ready(self) -> list[str]:
        return sorted(self.expected - self.seen)

    def lose(self, vid: str, at_s: float) -> None:
        """The vehicle was lost by a planned fault: it is over for it, and
        nothing it may still have said changes that."""
        v = self.vehicles.get(vid)
        if v is not None and v.lost_at_s is None:
            v.lost_at_s = at_s
            v.end_us = round(at_s * 1e6)
            v.cause = "planned fault"
            self.expected -= {n for n in self.expected if n.startswith(f"{vid}.")}

    def outcome(self, before_us: int | None = None) -> str | None:
        """None while any vehicle runs; else the worst vehicle outcome (a
        vehicle lost by a planned fault counts as over, not as a failure).
        before_us: only ends stamped before that sim time count."""
        outs = []
        for v in self.vehicles.values():  # called at every wake-up of the launcher: stop at the first running
            o = v.outcome
            if o is None or (before_us is not None and (v.end_us is None or v.end_us >= before_us)):
                return None
            outs.append(o)
        for worst in ("failed", "aborted"):
            if worst in outs:
                return worst
        return "done"

    def progress(self) -> list[str]:
        return [
            f"{vid} {v.path.split('/', 1)[-1] if v.path else '(loading)'}" + (f" [{v.outcome}]" if v.outcome else "")
            for vid, v in self.vehicles.items()
        ]

    def vehicle_summary(self) -> dict:
        return {
            vid: {
                "outcome": v.outcome,
                "path": v.path,
                "condition": v.condition,
                "cause": v.cause if v.outcome in ("aborted", "failed", "lost") else "",
                "lost_at_s": v.lost_at_s,
                "abort_condition": v.abort_condition,
                "abort_at_s": v.abort_at_s,
                "sim_time_s": None if v.sim_us is None else v.sim_us / 1e6,
            }
            for vid, v in self.vehicles.items()
        }

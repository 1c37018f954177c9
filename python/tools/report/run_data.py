"""Everything the report and the plots need from one run's log.

The log describes itself (docs/scenarios.md): the survey geometry, each
vehicle's simulator configuration and the launcher's outcome come from its
annotations, so a log file alone is enough.

Every series ends at the mission's end (docs/scenarios.md, "End"): the
launcher's `mission end` annotation; in a log without one (older logs, whose
world ran on while the processes stopped), the last vehicle's end (its plan
ended, or it was lost), else the launcher's summary. Messages stamped after
it are left out, whatever recorded them.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from auvlcm.arrays import ChannelArrays, LogArrays, load_log
from tools.logs.timeline import Segment, state_timeline

FINAL_RUNS = ("done", "aborted", "failed")  # a plan's run states that end it
END_MARK = "mission end"  # the launcher's annotation of the mission's end (tools/launch/launcher.py)
KIND_EVENT = 4  # log_annotation_t.KIND_EVENT
STEP_DONE = 1  # lockstep_t.KIND_STEP_DONE
# Paced by the wall clock, not by the mission: the multi-HIL clock sync, election and
# heartbeats, the recorder's health (once a wall second); not counted among its events.
WALL_PACED = ("SIM.CLOCK_SYNC", "SIM.ENV_HEARTBEAT", "SIM.ENV_ELECTION", "SIM.HEALTH")

KEEP = (
    r"SIM\.TARGETS|SIM\.ANNOTATION|.*\.CONTACTS"
    r"|.*\.TEAM_EVENT|.*\.MODEM_RX|.*\.MODEM_TX|.*\.MODEM_STATUS|.*\.LOOKS"
)  # the team section


@dataclass
class RunData:
    log: LogArrays
    vehicles: list[str]  # ids with ground truth in the log
    survey: dict | None = None  # the planner's survey.json
    outcome: dict | None = None  # the launcher's end event
    sim_configs: dict[str, str] = field(default_factory=dict)  # vehicle -> merged YAML text
    timelines: dict[str, list[Segment]] = field(default_factory=dict)  # "AUV1.NAVIGATOR" -> segments
    end_us: int | None = None  # the mission's end (sim time): every series is cut there
    end_from: str | None = None  # where end_us came from: "mark", "plans", "summary" (None: not cut)
    annotations_to_end: int = 0  # the launcher's notes up to and with the mark (all, without one)

    def truth(self, vid: str) -> ChannelArrays:
        return self.log[f"{vid}.TRUTH"]

    def nav(self, vid: str) -> ChannelArrays | None:
        return self.log.channels.get(f"{vid}.NAV")

    def targets(self) -> list[Any]:
        msgs = self.log.messages.get("SIM.TARGETS", [])
        return list(msgs[-1].targets) if msgs else []

    def contacts(self, vid: str) -> list[Any]:
        return self.log.messages.get(f"{vid}.CONTACTS", [])

    def duration_s(self) -> float:
        """Sim time from the first clock to the mission's end: when the last vehicle's
        plan ended (done, aborted, failed) or it was lost. The last clock up to the
        mission's end (cut_at_end) only when a vehicle never ended (the time limit)."""
        t0 = None
        if "SIM.CLOCK" in self.log and len(self.log["SIM.CLOCK"].t):
            t0 = float(self.log["SIM.CLOCK"].t[0])
        ends = [self._end_s(v) for v in self.vehicles]
        if t0 is not None and ends and None not in ends:
            return max(ends) - t0
        if t0 is not None:
            return float(self.log["SIM.CLOCK"].t[-1]) - t0
        return max((float(self.truth(v).t[-1] - self.truth(v).t[0]) for v in self.vehicles), default=0.0)

    def _end_s(self, vid: str) -> float | None:
        """When vid's mission ended: its first plan to end, or its loss (None: never)."""
        ends = [
            seg.start
            for name, segs in self.timelines.items()
            if name.startswith(f"{vid}.")
            for seg in segs
            if seg.run in FINAL_RUNS
        ]
        if ends:
            return min(ends)
        lost = ((self.outcome or {}).get("vehicles") or {}).get(vid, {}).get("lost_at_s")
        return float(lost) if lost is not None else None

    def mission_events(self) -> int:
        """The record's events of the mission: up to its end, each lockstep clock and
        report once (a repeat after a lost datagram or a slow step is the same message
        again), lockstep registrations and leaves and the wall-paced traffic (WALL_PACED)
        left out: what two runs of one seed have alike, whatever the machine's load."""
        n = self.log.stats.undecodable
        for ch, arr in self.log.channels.items():
            if ch in WALL_PACED or not len(arr):
                continue
            if ch == "SIM.ANNOTATION":
                n += self.annotations_to_end
            elif ch == "SIM.LOCKSTEP" and "kind" in arr.columns:
                done = arr["kind"] == STEP_DONE
                n += len(set(zip(arr["participant"][done], arr["step"][done])))
            elif ch == "SIM.CLOCK" and "step" in arr.columns:
                n += len(set(zip(arr["step"].tolist(), arr["utime"].tolist())))
            else:
                n += len(arr)
        return n

    def bathymetry(self):
        """depth(north, east) of the world, from a vehicle's configuration; None if unknown."""
        if not self.sim_configs:
            return None
        try:
            from sim.bathymetry import Bathymetry
            from sim.config import loads

            cfg = loads(next(iter(self.sim_configs.values())))
            return Bathymetry(cfg.env.bathymetry_ref, Path.cwd()).depth
        except Exception:  # noqa: BLE001 - a plot without a seabed beats no plot
            return None


def _json(text: str) -> dict | None:
    """An annotation's JSON; None if it does not parse (a damaged or foreign log)."""
    try:
        value = json.loads(text)
    except ValueError:
        return None
    return value if isinstance(value, dict) else None


def vehicle_order(vid: str) -> tuple:
    """Sort key for vehicle ids: AUV2 before AUV10 (the numbers as numbers)."""
    return tuple(int(part) if part.isdigit() else part for part in re.split(r"(\d+)", vid))


def _is_end_mark(ev) -> bool:
    m = ev.msg
    return ev.channel == "SIM.ANNOTATION" and getattr(m, "kind", None) == KIND_EVENT and m.name == END_MARK


def _timelines(run: RunData) -> None:
    for ch in run.log.matching(r"[A-Z][A-Z0-9]*\.CHASM\.[A-Z0-9_]+"):
        run.timelines[re.sub(r"\.CHASM\.", ".", ch)] = state_timeline(run.log[ch])


def _end_us(run: RunData, mark: Any) -> tuple[int | None, str | None]:
    """The mission's end: the launcher's mark; else the last vehicle's end; else its summary."""
    if mark is not None:
        return int(mark.utime), "mark"
    ends = [run._end_s(v) for v in run.vehicles]
    if ends and None not in ends:
        return round(max(ends) * 1e6), "plans"
    t = (run.outcome or {}).get("sim_time_s")
    if isinstance(t, (int, float)) and t > 0:
        return round(t * 1e6), "summary"
    return None, None


def cut_at_end(log: LogArrays, end_us: int) -> None:
    """Leave out every message stamped after end_us (the launcher's notes stay:
    they describe the run, and the stop is among them)."""
    for ch, arr in log.channels.items():
        if ch == "SIM.ANNOTATION" or "utime" not in arr.columns:
            continue
        keep = arr.columns["utime"] <= end_us
        if keep.all():
            continue
        arr.log_time_us = arr.log_time_us[keep]
        arr.columns = {k: v[keep] for k, v in arr.columns.items()}
        arr.ragged = {k: [x for x, ok in zip(v, keep) if ok] for k, v in arr.ragged.items()}
    for ch, msgs in log.messages.items():
        if ch != "SIM.ANNOTATION":
            log.messages[ch] = [m for m in msgs if getattr(m, "utime", 0) <= end_us]


def load_run(log_path: str | Path, survey_path: str | Path | None = None) -> RunData:
    log = load_log(log_path, keep_messages=KEEP, mark=_is_end_mark)
    vehicles = sorted((c.split(".")[0] for c in log.matching(r"[A-Z][A-Z0-9]*\.TRUTH")), key=vehicle_order)
    run = RunData(log, vehicles)
    mark = None
    notes = log.messages.get("SIM.ANNOTATION", [])
    run.annotations_to_end = len(notes)
    for i, a in enumerate(notes):
        if a.kind == 0 and a.name.endswith("survey.json") and run.survey is None:
            run.survey = _json(a.text)
        elif a.kind == 1 and a.vehicle and a.name.endswith(".sim.yaml"):
            run.sim_configs[a.vehicle] = a.text
        elif a.kind == KIND_EVENT and a.name == "end":
            run.outcome = _json(a.text)
        elif a.kind == KIND_EVENT and a.name == END_MARK and mark is None:
            mark, run.annotations_to_end = a, i + 1
    if survey_path is not None:
        run.survey = json.loads(Path(survey_path).read_text())
    _timelines(run)
    run.end_us, run.end_from = _end_us(run, mark)
    if run.end_us is not None:
        cut_at_end(log, run.end_us)
        run.timelines.clear()
        _timelines(run)
    return run


def interp_truth(run: RunData, vid: str, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """True north and east at the times t (linear between truth samples)."""
    tr = run.truth(vid)
    return np.interp(t, tr.t, tr["eta[0]"]), np.interp(t, tr.t, tr["eta[1]"])

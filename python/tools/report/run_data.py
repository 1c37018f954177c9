"""Everything the report and the plots need from one run's log.

The log describes itself (docs/scenarios.md): the survey geometry, each
vehicle's simulator configuration and the launcher's outcome come from its
annotations, so a log file alone is enough.
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
        plan ended (done, aborted, failed) or it was lost. The log's last clock only
        when a vehicle never ended: after the end the world's clock runs on while the
        launcher stops the processes, for as long as that takes (not the mission's time,
        and not the same in two runs)."""
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


def load_run(log_path: str | Path, survey_path: str | Path | None = None) -> RunData:
    log = load_log(log_path, keep_messages=KEEP)
    vehicles = sorted((c.split(".")[0] for c in log.matching(r"[A-Z][A-Z0-9]*\.TRUTH")), key=vehicle_order)
    run = RunData(log, vehicles)
    for a in log.messages.get("SIM.ANNOTATION", []):
        if a.kind == 0 and a.name.endswith("survey.json") and run.survey is None:
            run.survey = _json(a.text)
        elif a.kind == 1 and a.vehicle and a.name.endswith(".sim.yaml"):
            run.sim_configs[a.vehicle] = a.text
        elif a.kind == 4 and a.name == "end":
            run.outcome = _json(a.text)
    if survey_path is not None:
        run.survey = json.loads(Path(survey_path).read_text())
    for ch in log.matching(r"[A-Z][A-Z0-9]*\.CHASM\.[A-Z0-9_]+"):
        run.timelines[re.sub(r"\.CHASM\.", ".", ch)] = state_timeline(log[ch])
    return run


def interp_truth(run: RunData, vid: str, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """True north and east at the times t (linear between truth samples)."""
    tr = run.truth(vid)
    return np.interp(t, tr.t, tr["eta[0]"]), np.interp(t, tr.t, tr["eta[1]"])

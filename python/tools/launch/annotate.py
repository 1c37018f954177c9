"""Make a log self-describing: the files a run used, written into it at start.

Channel SIM.ANNOTATION, type log_annotation_t: the scenario (KIND_SCENARIO),
each vehicle's merged simulator configuration (KIND_SCENARIO, with vehicle),
each plan and the files it includes (KIND_PLAN), each binding file and the
files it includes (KIND_NOTE named after the file), every .lcm type definition (KIND_LCMTYPE), and
supervisor events (KIND_EVENT: process start/exit, mission end).
`auv-lcmlog annotations LOG --extract DIR` writes them back out.
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import lcm

from auv import log_annotation_t

CHANNEL = "SIM.ANNOTATION"
PACE_S = 0.003  # between annotations
_INCLUDE = re.compile(r'^\s*include\s+"([^"]+)"', re.M)


def plan_files(plan: Path) -> list[Path]:
    """A plan and every file it includes, each once, includes resolved as CHASM does."""
    seen: list[Path] = []
    todo = [plan.resolve()]
    while todo:
        p = todo.pop(0)
        if p in seen or not p.is_file():
            continue
        seen.append(p)
        todo += [(p.parent / inc).resolve() for inc in _INCLUDE.findall(p.read_text())]
    return seen


def display_name(path: Path, root: Path) -> str:
    try:
        return str(path.resolve().relative_to(root))
    except ValueError:
        return str(path)


class Annotator:
    def __init__(self, lc: lcm.LCM, source: str, root: Path, paced: bool = True) -> None:
        self.lc, self.source, self.root, self.paced = lc, source, root, paced
        self.count = 0

    def note(self, kind: int, name: str, text: str, vehicle: str = "", utime: int = 0) -> None:
        a = log_annotation_t()
        a.utime, a.vehicle, a.source, a.kind, a.name, a.text = utime, vehicle, self.source, kind, name, text
        self.lc.publish(CHANNEL, a.encode())
        self.count += 1
        # A burst of ~60 files at start overran lcm-logger on a loaded 2-core
        # machine (half the type definitions went missing): pace them for it.
        if self.paced:
            time.sleep(PACE_S)

    def file(self, kind: int, path: Path, vehicle: str = "") -> None:
        self.note(kind, display_name(path, self.root), path.read_text(), vehicle)

    def event(self, name: str, text: str, vehicle: str = "", utime: int = 0) -> None:
        self.note(log_annotation_t.KIND_EVENT, name, text, vehicle, utime)

    def types(self) -> None:
        for p in sorted((self.root / "lcmtypes").glob("*.lcm")):
            self.file(log_annotation_t.KIND_LCMTYPE, p)

    def plan(self, plan: Path, vehicle: str) -> None:
        for p in plan_files(plan):
            self.file(log_annotation_t.KIND_PLAN, p, vehicle)

    def run(self, sc, sim_configs: dict, nav_configs: dict) -> None:
        """What a run is noted with at its start: the scenario, its survey, each
        vehicle's simulator and nav configurations (sc: a tools.scenario Scenario;
        configs by vehicle id, where it has them), plans and bindings, the types."""
        self.note(log_annotation_t.KIND_SCENARIO, sc.path.name, sc.text)
        if sc.survey is not None:
            self.note(log_annotation_t.KIND_NOTE, sc.survey.name, sc.survey.read_text())
        for v in sc.vehicles:
            for configs in (sim_configs, nav_configs):
                if v.id in configs:
                    self.note(log_annotation_t.KIND_SCENARIO, configs[v.id].name, configs[v.id].read_text(), v.id)
            for m in v.managers:
                self.plan(m.plan, v.id)
                self.binding(m.bind, v.id)
        self.types()

    def binding(self, bind: Path, vehicle: str) -> None:
        # a binding file's `include "FILE"` has the plans' syntax and resolution
        for p in plan_files(bind):
            self.file(log_annotation_t.KIND_NOTE, p, vehicle)

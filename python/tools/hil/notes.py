"""The annotations of a run flown at the wire, written into its merged log.

The launcher annotates a run as it starts and ends (tools/launch/launcher.py:
the scenario, the survey, each vehicle's configurations, plans and bindings,
the message types; `mission end`; the `end` summary), and the report reads
them. At the wire no process sees every world (the orchestrator may run where
none of them is heard), so the same notes are made offline and written into
run.lcmlog beside the worlds' events: the first ones before the first event,
the end after the last.
"""

from __future__ import annotations

import json
from pathlib import Path

from auvlcm.offline import OfflineLcm
from auvlcm.paths import ROOT
from tools.launch.annotate import Annotator
from tools.scenario.scenario_file import Scenario


def start_notes(sc: Scenario, files: dict[str, dict[str, Path]]) -> list[tuple[str, bytes]]:
    """What the launcher notes at the start; files[vid]: its wired `sim` and `nav` configs."""
    lc = OfflineLcm(keep=True)
    sims = {vid: f["sim"] for vid, f in files.items()}
    navs = {vid: f["nav"] for vid, f in files.items()}
    Annotator(lc, "auv-hil-wire", ROOT, paced=False).run(sc, sims, navs)
    return lc.published


def end_notes(end_us: int, summary: dict) -> list[tuple[str, bytes]]:
    """The mission's end (the last vehicle computer's) and the run's summary."""
    lc = OfflineLcm(keep=True)
    notes = Annotator(lc, "auv-hil-wire", ROOT, paced=False)
    notes.event("mission end", json.dumps({"sim_time_s": end_us / 1e6}), utime=end_us)
    notes.event("end", json.dumps(summary), utime=end_us)
    return lc.published

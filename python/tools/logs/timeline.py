"""A CHASM's state timeline from its chasm_status_t messages in a log."""

from __future__ import annotations

from dataclasses import dataclass

from auvlcm.arrays import ChannelArrays

RUN_NAMES = ("loading", "running", "paused", "done", "aborted", "failed")


def run_name(code: int) -> str:
    return RUN_NAMES[code] if 0 <= code < len(RUN_NAMES) else str(code)


@dataclass
class Segment:
    start: float  # sim time the segment began [s]
    end: float  # sim time of the last status in it [s]
    path: str  # active path "mission/survey/line3"
    run: str  # run state name
    condition: str  # the condition that led into it ("" for the first)


def state_timeline(status: ChannelArrays) -> list[Segment]:
    """Consecutive statuses with the same active path and run state, merged."""
    t = status.t
    runs = status["run_state"]
    conds = status["last_condition"]
    paths = status.ragged["active_path"]
    out: list[Segment] = []
    for i in range(len(status)):
        path, run = "/".join(paths[i]), run_name(int(runs[i]))
        if out and out[-1].path == path and out[-1].run == run:
            out[-1].end = float(t[i])
            continue
        out.append(Segment(float(t[i]), float(t[i]), path, run, str(conds[i]) if out else ""))
    return out

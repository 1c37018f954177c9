"""The team mission's plots (auv-report, with tools/report/plots.py's conventions).

heard.*     who heard whom over time: one row per sender->receiver pair, a dot
            per frame received (<V>.MODEM_RX)
ri_route.*  the RI vehicle's track and its last planned route over the true
            targets and the search vehicles' mine-like contacts (CONTACT_NEW),
            identifications marked by result
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from tools.report import team_report as tr
from tools.report.plots import _area, _save, vehicle_colour
from tools.report.run_data import RunData


def heard(run: RunData, out: Path, t0: float) -> list[Path]:
    pairs = tr.who_heard_whom(run, t0)
    if not pairs:
        return []
    fig, ax = plt.subplots(figsize=(9, 1.2 + 0.35 * len(pairs)))
    for y, (pair, times) in enumerate(pairs.items()):
        src = pair.split("->")[0]
        ax.plot(np.array(times) / 60, [y] * len(times), "|", ms=9, color=vehicle_colour(run, src))
    ax.set_yticks(range(len(pairs)), list(pairs))
    ax.set_xlabel("sim time [min]")
    ax.set_title("who heard whom (a mark per frame received; colour: sender)")
    ax.grid(axis="x", alpha=0.3)
    return _save(fig, out, "heard")


def ri_route(run: RunData, out: Path, team: dict, t0: float) -> list[Path]:
    evs = tr.events(run)
    fig, ax = plt.subplots(figsize=(7, 7))
    _area(ax, run)
    targets = run.targets()
    for kind, colour, label in ((0, "red", "mine-like (truth)"), (1, "grey", "clutter (truth)")):
        pts = [(t.east_m, t.north_m) for t in targets if t.kind == kind]
        if pts:
            ax.scatter(*zip(*pts), marker="x", color=colour, s=40, label=label, zorder=3)
    new = [e for e in evs if e.kind == tr.CONTACT_NEW]
    if new:
        ax.scatter(
            [e.east_m for e in new],
            [e.north_m for e in new],
            facecolors="none",
            edgecolors="b",
            s=70,
            label="reported contacts",
            zorder=3,
        )
    for vid in team["ri_vehicles"]:
        if f"{vid}.TRUTH" in run.log:
            truth = run.truth(vid)
            ax.plot(truth["eta[1]"], truth["eta[0]"], color=vehicle_colour(run, vid), lw=1, label=f"{vid} track")
    queued = {f"{e.origin}:{e.number}": (e.east_m, e.north_m) for e in evs if e.kind == tr.TARGET_QUEUED}
    if team["routes"]:
        order = [queued[k] for k in team["routes"][-1]["order"] if k in queued]
        if order:
            ax.plot(*zip(*order), "k--", lw=1, label="last planned route")
    for result, marker, label in (("mine", "s", "identified: mine"), ("not_mine", "D", "identified: not mine")):
        pts = [
            (e.east_m, e.north_m)
            for e in evs
            if e.kind == tr.TARGET_IDENTIFIED and {1: "mine", 2: "not_mine"}.get(int(e.result)) == result
        ]
        if pts:
            ax.scatter(*zip(*pts), marker=marker, facecolors="none", edgecolors="k", s=110, label=label, zorder=4)
    ax.set_aspect("equal")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_title("RI route over the contacts and the true targets")
    ax.legend(fontsize=7, loc="best")
    return _save(fig, out, "ri_route")


def team_plots(run: RunData, team: dict, out: Path) -> list[Path]:
    t0 = float(run.log["SIM.CLOCK"].t[0]) if "SIM.CLOCK" in run.log and len(run.log["SIM.CLOCK"].t) else 0.0
    return heard(run, out, t0) + (ri_route(run, out, team, t0) if team.get("ri_vehicles") else [])

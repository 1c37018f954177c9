"""The run's plots, PNG and SVG (matplotlib, Agg backend: no display needed).

tracks.*    true tracks (and NAV, dashed) over the bathymetry, with the survey area
coverage.*  looks per cell of the coverage grid, with the survey area
contacts.*  contacts against the true targets, association radius drawn, missed
            mine-like targets and false alarms marked
depth.*     depth (left axis, down) and altitude (right axis) over time, per vehicle
states.*    each CHASM's leaf-state timeline, aborts marked with their cause

Colours stay the same between runs: a vehicle's from its name's place among
the vehicles, a state's from its name (state_colour: never red, red marks aborts).
"""

from __future__ import annotations

import zlib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Polygon as MplPolygon

from tools.report.association import associate
from tools.report.run_data import RunData

FORMATS = ("png", "svg")


def vehicle_colour(run: RunData, vid: str):
    return plt.get_cmap("tab10")(sorted(run.vehicles).index(vid) % 10 if vid in run.vehicles else 9)


# tab20 without its two reds (6, 7): red marks aborts and nothing else; then tab20b
# without its red group (12-15) and tab20c, for more names
STATE_PALETTE = (
    [plt.get_cmap("tab20")(i) for i in range(20) if i not in (6, 7)]
    + [plt.get_cmap("tab20b")(i) for i in range(20) if not 12 <= i < 16]
    + [plt.get_cmap("tab20c")(i) for i in range(16)]
)
# The leaf states of the shipped and planned missions, each its own colour (their
# index in STATE_PALETTE), chosen so that the ones a plot shows together are far
# apart; another name takes its name's hash's (so a name's colour never depends on
# what else a run holds; two such names may share one)
KNOWN_STATES = {
    "survey": 0,  # blue
    "dive": 1,  # light blue
    "route": 2,  # orange
    "transit": 3,  # light orange
    "reacquire": 4,  # green
    "mission": 5,  # light green
    "linger": 6,  # purple
    "altitude": 7,  # light purple
    "recover": 8,  # brown
    "surface": 9,  # light brown
    "follow": 10,  # pink
    "alone": 11,  # light pink
    "emergency": 12,  # grey (its abort is the red mark and the hatching)
    "idle": 13,  # light grey
    "gps_fix": 14,  # olive
    "line": 15,  # light olive
    "depth": 16,  # cyan
    "transect": 17,  # light cyan
    # the box survey's legs (missions/box_survey): lines dark, turns pale
    "line1": 18,
    "line2": 22,
    "line3": 26,
    "line4": 30,
    "line5": 34,
    "turn2": 24,
    "turn3": 28,
    "turn4": 32,
    "turn5": 37,
    "initial_fix": 20,
    "climb": 40,
    "fly": 44,
    "frontseat_lost": 48,
    "pitch": 19,
    "rpm": 23,
    "mps": 27,
    "lines": 42,
    "leg2": 21,  # missions/frontseat/backseat_line.chasm
    "zigzag": 25,  # missions/examples/ctd_zigzag.chasm (sampling)
    "mow": 29,  # missions/scenarios/sampling_lawnmower (the baseline)
}


def state_colour(name: str):
    """From the name alone, never red (red marks aborts)."""
    k = KNOWN_STATES.get(name)
    return STATE_PALETTE[k if k is not None else zlib.crc32(name.encode()) % len(STATE_PALETTE)]


def _save(fig, out: Path, name: str) -> list[Path]:
    paths = []
    for ext in FORMATS:
        p = out / f"{name}.{ext}"
        fig.savefig(p, dpi=110, bbox_inches="tight")
        paths.append(p)
    plt.close(fig)
    return paths


def _area(ax, run: RunData) -> None:
    """Survey area (and operating area) outlines, in (east, north) axes."""
    if not run.survey:
        return
    poly = np.array(run.survey["polygon"])
    ax.add_patch(MplPolygon(poly[:, ::-1], closed=True, fill=False, ec="k", lw=1.5, label="survey area"))
    op = np.array(run.survey.get("operating_area") or [])
    if len(op):
        ax.add_patch(MplPolygon(op[:, ::-1], closed=True, fill=False, ec="r", lw=0.8, ls=":", label="operating area"))


def _extent(run: RunData, pad: float = 30.0):
    pts = [np.column_stack([run.truth(v)["eta[1]"], run.truth(v)["eta[0]"]]) for v in run.vehicles]
    if run.survey:
        pts.append(np.array(run.survey["polygon"])[:, ::-1])
    allp = np.vstack(pts)
    return allp[:, 0].min() - pad, allp[:, 0].max() + pad, allp[:, 1].min() - pad, allp[:, 1].max() + pad


def tracks(run: RunData, out: Path) -> list[Path]:
    fig, ax = plt.subplots(figsize=(8, 7))
    e0, e1, n0, n1 = _extent(run)
    depth = run.bathymetry()
    if depth is not None:
        ee, nn = np.meshgrid(np.linspace(e0, e1, 120), np.linspace(n0, n1, 120))
        zz = np.vectorize(depth)(nn, ee)
        lo, hi = float(zz.min()), float(zz.max())
        flat = hi - lo < 0.05  # a flat seabed: one band and one tick, not 14 levels of noise
        levels = [lo - 0.5, hi + 0.5] if flat else 14
        cs = ax.contourf(ee, nn, zz, levels=levels, cmap="Blues", vmin=lo - 5 if flat else None)
        cs.set_rasterized(True)
        fig.colorbar(cs, ax=ax, label="water depth [m]", ticks=[round((lo + hi) / 2, 1)] if flat else None)
    _area(ax, run)
    for vid in run.vehicles:
        tr = run.truth(vid)
        (line,) = ax.plot(tr["eta[1]"], tr["eta[0]"], lw=1.2, label=f"{vid} true", color=vehicle_colour(run, vid))
        nav = run.nav(vid)
        if nav is not None and len(nav):
            ax.plot(nav["east_m"], nav["north_m"], lw=0.7, ls="--", color=line.get_color(), label=f"{vid} NAV")
        ax.plot(tr["eta[1]"][0], tr["eta[0]"][0], "o", color=line.get_color())
    ax.set(xlabel="east [m]", ylabel="north [m]", title="Tracks", xlim=(e0, e1), ylim=(n0, n1), aspect="equal")
    ax.legend(fontsize=7, loc="upper right")
    return _save(fig, out, "tracks")


def coverage(run: RunData, grid, out: Path) -> list[Path]:
    fig, ax = plt.subplots(figsize=(8, 7))
    n, e = grid.centres()
    top = max(3, int(grid.looks.max()))
    im = ax.pcolormesh(
        e,
        n,
        np.ma.masked_equal(grid.looks, 0),
        cmap=plt.get_cmap("viridis", top),
        vmin=0.5,
        vmax=top + 0.5,
        shading="nearest",
        rasterized=True,
    )  # an image inside the SVG, not one path per cell
    fig.colorbar(im, ax=ax, label="looks per cell", ticks=range(1, top + 1))
    _area(ax, run)
    once = grid.area_with(1) / max(1.0, float(np.count_nonzero(grid.inside)) * grid.cell**2)
    ax.set(
        xlabel="east [m]",
        ylabel="north [m]",
        aspect="equal",
        title=f"Sidescan coverage: {100 * once:.1f} % of the area seen at least once",
    )
    return _save(fig, out, "coverage")


def contacts(run: RunData, out: Path, radius: float = 5.0) -> list[Path]:
    fig, ax = plt.subplots(figsize=(8, 7))
    _area(ax, run)
    targets = run.targets()
    for kind, style, label in (
        (0, dict(marker="^", color="red", ms=8), "mine-like target"),
        (1, dict(marker="s", color="grey", ms=6), "clutter"),
    ):
        pts = np.array([(t.east_m, t.north_m) for t in targets if t.kind == kind]).reshape(-1, 2)
        if len(pts):
            ax.plot(pts[:, 0], pts[:, 1], ls="none", mfc="none", label=label, **style)
            for x, y in pts:
                ax.add_patch(plt.Circle((x, y), radius, fill=False, lw=0.4, color=style["color"]))
    for vid in run.vehicles:
        c = np.array([(m.east_m, m.north_m) for m in run.contacts(vid)]).reshape(-1, 2)
        if len(c):
            ax.plot(c[:, 0], c[:, 1], "x", ms=5, label=f"{vid} contacts", color=vehicle_colour(run, vid))
    a = associate(targets, [(vid, c) for vid in run.vehicles for c in run.contacts(vid)], radius)
    missed = np.array([(t.east_m, t.north_m) for t, m in zip(targets, a.missed) if m]).reshape(-1, 2)
    if len(missed):
        ax.plot(
            missed[:, 0],
            missed[:, 1],
            "o",
            ms=16,
            mfc="none",
            mec="red",
            mew=2,
            label=f"missed mine-like ({len(missed)})",
        )
    fa = np.array([(c.east_m, c.north_m) for (_v, c), f in zip(a.contacts, a.false_alarm) if f]).reshape(-1, 2)
    if len(fa):
        ax.plot(fa[:, 0], fa[:, 1], "o", ms=11, mfc="none", mec="darkorange", mew=1.5, label=f"false alarm ({len(fa)})")
    e0, e1, n0, n1 = _extent(run)
    ax.set(
        xlabel="east [m]",
        ylabel="north [m]",
        title="Contacts and true targets",
        aspect="equal",
        xlim=(e0, e1),
        ylim=(n0, n1),
    )
    ax.legend(fontsize=7, loc="upper right")
    return _save(fig, out, "contacts")


def depth(run: RunData, out: Path) -> list[Path]:
    fig, axes = plt.subplots(len(run.vehicles), 1, figsize=(9, 2.4 * len(run.vehicles)), sharex=True, squeeze=False)
    for ax, vid in zip(axes[:, 0], run.vehicles):
        tr = run.truth(vid)
        t = tr.t / 60
        ax.plot(t, tr["eta[2]"], label="depth", color=vehicle_colour(run, vid))
        ax.plot(t, tr["water_depth_m"], lw=0.6, color="k", label="water depth")
        ax.invert_yaxis()
        ax.set_ylabel(f"{vid} depth [m]")
        # altitude has its own axis, up: on the depth axis a few metres over a deep seabed vanish
        alt_ax = ax.twinx()
        alt = np.where(tr["altitude_m"] >= 0, tr["altitude_m"], np.nan)
        alt_ax.plot(t, alt, lw=0.9, color="tab:green", label="altitude")
        alt_ax.set_ylabel("altitude [m]", color="tab:green")
        alt_ax.set_ylim(bottom=0)
        lines = ax.get_lines() + alt_ax.get_lines()
        ax.legend(lines, [ln.get_label() for ln in lines], fontsize=7, loc="lower right", ncol=3)
    axes[-1, 0].set_xlabel("sim time [min]")
    axes[0, 0].set_title("Depth and altitude")
    return _save(fig, out, "depth")


def states(run: RunData, out: Path) -> list[Path]:
    keys = sorted(run.timelines)
    fig, ax = plt.subplots(figsize=(10, 0.6 * len(keys) + 1.2))
    names = sorted({_leaf(s) for k in keys for s in run.timelines[k]})
    colors = {n: state_colour(n) for n in names}
    causes = (run.outcome or {}).get("vehicles", {})
    for y, k in enumerate(keys):
        segs = run.timelines[k]
        vid, mgr = k.split(".", 1)
        v = causes.get(vid, {})
        if v.get("cause") and v.get("abort_at_s") is not None and mgr == "NAVIGATOR":
            _mark_abort(ax, v["abort_at_s"], y, v["cause"])
        elif not v.get("cause"):  # no launcher outcome: the aborted or failed segments say why
            for s in segs:
                if s.run in ("aborted", "failed") and s.condition:
                    _mark_abort(ax, s.start, y, s.condition)
                    break
        for i, s in enumerate(segs):
            name = _leaf(s)
            end = segs[i + 1].start if i + 1 < len(segs) else s.end  # a state lasts until the next one
            width = max(end - s.start, 0.1) / 60
            ax.broken_barh(
                [(s.start / 60, width)],
                (y - 0.35, 0.7),
                color=colors[name],
                hatch="//" if s.run in ("aborted", "failed") else None,
            )
    ax.set_yticks(range(len(keys)), keys)
    ax.set_xlabel("sim time [min]")
    ax.set_title("CHASM state timelines (colour: leaf state; red: abort and its cause)")
    handles = [plt.Rectangle((0, 0), 1, 1, color=colors[n]) for n in names[:20]]
    ax.legend(handles, names[:20], fontsize=6, ncol=5, loc="upper center", bbox_to_anchor=(0.5, -0.25))
    return _save(fig, out, "states")


def _leaf(seg) -> str:
    return seg.path.rsplit("/", 1)[-1] if seg.path else seg.run


def _mark_abort(ax, t_s: float, y: int, cause: str) -> None:
    ax.plot([t_s / 60] * 2, [y - 0.45, y + 0.45], color="red", lw=2)
    ax.annotate(
        cause, (t_s / 60, y + 0.4), fontsize=7, color="red", xytext=(3, 0), textcoords="offset points", va="bottom"
    )


def make_plots(run: RunData, grid, out: Path) -> list[Path]:
    out.mkdir(parents=True, exist_ok=True)
    paths = tracks(run, out) + depth(run, out)
    if grid is not None:
        paths += coverage(run, grid, out)
    if run.targets() or any(run.contacts(v) for v in run.vehicles):
        paths += contacts(run, out)
    if run.timelines:
        paths += states(run, out)
    return paths

"""The sampling mission's plots (auv-report, with tools/report/plots.py's conventions).

front_field.*  the world's temperature at the estimator's depth at the mission's end,
               the tracks, the CTD samples, the true front (its mid-temperature line)
               and each vehicle's last team estimate of it beside the truth
front_error.*  the map error over time: the team's estimates and the own-samples ones
section.*      a vertical section: each vehicle's CTD temperature against distance run and depth
ts.*           the temperature-salinity diagram of every CTD sample, with density (sigma-0) contours
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from tools.report import front_grade as fg
from tools.report.plots import _save, vehicle_colour
from tools.report.run_data import RunData

MAX_POINTS = 4000  # CTD samples drawn per vehicle (every k-th)


def _ctd(run: RunData, vid: str):
    arr = run.log.channels.get(f"{vid}.CTD")
    if arr is None or not len(arr):
        return None
    ok = arr["valid"].astype(bool) & np.isfinite(arr["temperature_c"])
    k = max(1, int(np.count_nonzero(ok) // MAX_POINTS))
    return {c: arr[c][ok][::k] for c in ("temperature_c", "salinity_psu", "depth_m")} | {"t": arr.t[ok][::k]}


def front_field(run: RunData, grade: dict, out: Path) -> list[Path]:
    ocean = fg.world_ocean(run)
    n0, n1, e0, e1 = grade["area"]
    ee, nn = np.meshgrid(np.linspace(e0, e1, 160), np.linspace(n0, n1, 160))
    t_end = grade["curve"]["t"][-1] if grade["curve"]["t"] else 0.0
    temp = ocean.fields(t_end, nn, ee, grade["depth_m"])[0]
    fig, ax = plt.subplots(figsize=(8, 7))
    cs = ax.contourf(ee, nn, temp, levels=20, cmap="RdYlBu_r")
    cs.set_rasterized(True)
    fig.colorbar(cs, ax=ax, label=f"true temperature at {grade['depth_m']:g} m [degC]")
    truth = fg.true_front(ocean)
    mid = (truth["temperature_a_c"] + truth["temperature_b_c"]) / 2
    ax.contour(ee, nn, temp, levels=[mid], colors="k", linewidths=1.6)
    ax.plot([], [], "k-", label="the front (truth)")
    last = {v: s for v, s in ((v, fg._estimates(run, f"{v}.FRONT_TEAM")) for v in run.vehicles) if s}
    for vid in run.vehicles:
        colour = vehicle_colour(run, vid)
        tr = run.truth(vid)
        ax.plot(tr["eta[1]"], tr["eta[0]"], lw=0.8, color=colour, label=f"{vid} track")
        ests = [e for _, e in last.get(vid, []) if e is not None]
        if ests:
            est_t = fg.model_temperature(ests[-1], nn.ravel(), ee.ravel()).reshape(nn.shape)
            est_mid = (ests[-1]["temperature_a_c"] + ests[-1]["temperature_b_c"]) / 2
            ax.contour(ee, nn, est_t, levels=[est_mid], colors=[colour], linewidths=1.2, linestyles="--")
            ax.plot([], [], "--", color=colour, label=f"{vid} team estimate")
    ax.set(xlabel="east [m]", ylabel="north [m]", aspect="equal", xlim=(e0, e1), ylim=(n0, n1))
    ax.set_title(f"the front at {t_end / 60:.1f} min: estimates (dashed) beside the truth")
    ax.legend(fontsize=7, loc="upper left")
    return _save(fig, out, "front_field")


def front_error(run: RunData, grade: dict, out: Path) -> list[Path]:
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(np.array(grade["curve"]["t"]) / 60, grade["curve"]["team"], "k-", label="with teammates' summaries")
    ax.plot(np.array(grade["own_curve"]["t"]) / 60, grade["own_curve"]["own"], "k--", label="own samples alone")
    ax.axhline(grade["spread_c"], color="grey", lw=0.8, ls=":", label="knowing nothing (the water's spread)")
    ax.set(xlabel="sim time [min]", ylabel="map error, rms [degC]", yscale="log")
    ax.set_title("the team's map error against the world's field (mean over vehicles)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    return _save(fig, out, "front_error")


def section(run: RunData, out: Path) -> list[Path]:
    data = {v: _ctd(run, v) for v in run.vehicles}
    data = {v: d for v, d in data.items() if d is not None and len(d["t"])}
    if not data:
        return []
    fig, axes = plt.subplots(len(data), 1, figsize=(9, 1.8 + 1.6 * len(data)), squeeze=False, sharex=True)
    lo = min(float(d["temperature_c"].min()) for d in data.values())
    hi = max(float(d["temperature_c"].max()) for d in data.values())
    for ax, (vid, d) in zip(axes[:, 0], data.items()):
        tr = run.truth(vid)
        run_m = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(tr["eta[0]"]), np.diff(tr["eta[1]"])))])
        dist = np.interp(d["t"], tr.t, run_m)
        sc = ax.scatter(dist, d["depth_m"], c=d["temperature_c"], s=3, cmap="RdYlBu_r", vmin=lo, vmax=hi)
        ax.invert_yaxis()
        ax.set_ylabel(f"{vid}\ndepth [m]")
    axes[-1, 0].set_xlabel("distance run [m]")
    fig.colorbar(sc, ax=axes[:, 0], label="CTD temperature [degC]")
    axes[0, 0].set_title("vertical section: CTD temperature along each vehicle's path")
    return _save(fig, out, "section")


def ts_diagram(run: RunData, out: Path) -> list[Path]:
    import gsw

    data = {v: _ctd(run, v) for v in run.vehicles}
    data = {v: d for v, d in data.items() if d is not None and len(d["t"])}
    if not data:
        return []
    fig, ax = plt.subplots(figsize=(6, 5))
    s_all = np.concatenate([d["salinity_psu"] for d in data.values()])
    t_all = np.concatenate([d["temperature_c"] for d in data.values()])
    ss, tt = np.meshgrid(
        np.linspace(s_all.min() - 0.2, s_all.max() + 0.2, 60), np.linspace(t_all.min() - 0.5, t_all.max() + 0.5, 60)
    )
    sa = gsw.SA_from_SP(ss, 0.0, 0.0, 0.0)  # near the surface: in-situ ~ potential temperature
    cs = ax.contour(ss, tt, gsw.sigma0(sa, gsw.CT_from_t(sa, tt, 0.0)), colors="grey", linewidths=0.6)
    ax.clabel(cs, fontsize=7, fmt="%.1f")
    for vid, d in data.items():
        ax.scatter(d["salinity_psu"], d["temperature_c"], s=2, alpha=0.4, color=vehicle_colour(run, vid), label=vid)
    ax.set(xlabel="practical salinity [PSU]", ylabel="temperature [degC]")
    ax.set_title("T-S diagram (contours: sigma-0 [kg/m3])")
    ax.legend(fontsize=8, markerscale=4)
    return _save(fig, out, "ts")


def sampling_plots(run: RunData, grade: dict, out: Path) -> list[Path]:
    paths = section(run, out) + ts_diagram(run, out)
    if grade.get("curve", {}).get("t"):
        paths += front_field(run, grade, out) + front_error(run, grade, out)
    return paths

"""Monte Carlo figures: per-run metrics from a mission report, and their
summary over the runs as mean and 95 % interval, as text, JSON and a plot.

The interval is the 95 % confidence interval of the mean (Student's t over
the runs): what a user needs to tell a change in their plan from noise. Each
figure has the range it can take (a count is never negative, a fraction never
over 1): the interval is cut to it and says so. Under MIN_N runs no interval is
given (two runs make a t-interval 12.7 standard errors wide): the summary says
n is too small and shows the runs' range."""

from __future__ import annotations

import math
from pathlib import Path

INF = math.inf
MIN_N = 3  # runs for an interval

# (key, label, unit, scale to the unit, the figure's range in its own units)
METRICS = [
    ("coverage", "coverage once", "%", 100.0, (0.0, 1.0)),
    ("pd", "PD (mine-like, covered area)", "", 1.0, (0.0, 1.0)),
    ("false_alarms", "false alarms", "", 1.0, (0.0, INF)),
    ("nav_error_rms_m", "nav error rms (mean of vehicles)", "m", 1.0, (0.0, INF)),
    ("mission_time_s", "mission time", "min", 1 / 60, (0.0, INF)),
    # a team mission's own figures (auv-report's team section, docs/team.md)
    ("mine_like_identified", "team: mine-like identified", "", 1.0, (0.0, INF)),
    ("identified_fraction", "team: identified / mine-like", "%", 100.0, (0.0, 1.0)),
    ("false_identifications", "team: false identifications", "", 1.0, (0.0, INF)),
    ("detect_to_identify_s", "team: detection to identification", "min", 1 / 60, (0.0, INF)),
    # a sampling mission's grade (auv-report's sampling section, docs/sampling.md)
    ("team_map_rms_c", "sampling: map error, team", "degC", 1.0, (0.0, INF)),
    ("own_map_rms_c", "sampling: map error, own samples", "degC", 1.0, (0.0, INF)),
    ("half_spread_s", "sampling: to half the spread", "min", 1 / 60, (0.0, INF)),
]

# two-sided 95 % Student t quantiles for 1..30 degrees of freedom; 1.96 beyond
_T95 = [
    12.706,
    4.303,
    3.182,
    2.776,
    2.571,
    2.447,
    2.365,
    2.306,
    2.262,
    2.228,
    2.201,
    2.179,
    2.160,
    2.145,
    2.131,
    2.120,
    2.110,
    2.101,
    2.093,
    2.086,
    2.080,
    2.074,
    2.069,
    2.064,
    2.060,
    2.056,
    2.052,
    2.048,
    2.045,
    2.042,
]


def metrics_of(rep: dict) -> dict:
    """The figures that matter, from auv-report's JSON (None where a run has none)."""
    cov, det = rep.get("coverage") or {}, rep.get("detection") or {}
    nav = [e["rms_m"] for e in rep.get("navigation_error", {}).values()]
    pd = det.get("pd_in_covered_area", det.get("pd"))
    team = rep.get("team") or {}
    if not team.get("mine_like_targets"):
        team = {}  # a team that hunted no mines (a sampling team): no MCM figures
    mines = team.get("mine_like_targets")
    grade = rep.get("sampling") or {}
    lat = team.get("detect_to_identify_s") or {}
    return {
        "coverage": cov.get("fraction_once"),
        "pd": pd,
        "false_alarms": det.get("false_alarms"),
        "nav_error_rms_m": sum(nav) / len(nav) if nav else None,
        "mission_time_s": rep.get("duration_s"),
        "mine_like_identified": team.get("mine_like_identified"),
        "identified_fraction": team["mine_like_identified"] / mines if mines else None,
        "false_identifications": len(team["false_identifications"]) if "false_identifications" in team else None,
        "detect_to_identify_s": lat.get("mean"),
        "team_map_rms_c": grade.get("team_map_rms_c"),
        "own_map_rms_c": grade.get("own_map_rms_c"),
        "half_spread_s": grade.get("first_under_half_spread_s"),
        "outcome": rep.get("outcome"),
        "truth_samples_lost": sum(r["missing"] for r in rep.get("record", {}).values()),
    }


def interval(values: list[float], bounds: tuple[float, float] = (-INF, INF)) -> dict:
    """Mean and 95 % confidence interval of the mean, cut to the figure's range
    (`clipped` says it was); under MIN_N values no interval (lo, hi None) and
    `too_few` says why."""
    n = len(values)
    mean = sum(values) / n
    out = {"n": n, "mean": mean, "min": min(values), "max": max(values)}
    if n < MIN_N:
        return {**out, "lo": None, "hi": None, "too_few": f"n {n} is too small for an interval (at least {MIN_N})"}
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    half = (_T95[n - 2] if n - 1 <= len(_T95) else 1.96) * sd / math.sqrt(n)
    lo, hi = max(bounds[0], mean - half), min(bounds[1], mean + half)
    return {**out, "lo": lo, "hi": hi, "sd": sd, "clipped": lo != mean - half or hi != mean + half}


def summarize(runs: list[dict]) -> dict:
    ok = [r for r in runs if r.get("metrics")]
    out = {
        "runs": len(runs),
        "reported": len(ok),
        "outcomes": {
            o: sum(1 for r in ok if r["metrics"]["outcome"] == o)
            for o in sorted({r["metrics"]["outcome"] or "-" for r in ok})
        },
        "failed_runs": {str(r["seed"]): r.get("error", "") for r in runs if not r.get("metrics")},
        "metrics": {},
        # a team mission's runs: its figures are listed (with "-" where none came)
        "team": any(r["metrics"].get("mine_like_identified") is not None for r in ok),
        "sampling": any(r["metrics"].get("team_map_rms_c") is not None for r in ok),
    }
    for key, _label, _unit, _scale, bounds in METRICS:
        vals = [r["metrics"][key] for r in ok if r["metrics"].get(key) is not None]
        if vals:
            out["metrics"][key] = interval([float(v) for v in vals], bounds)
    return out


TEAM_KEYS = ("mine_like_identified", "identified_fraction", "false_identifications", "detect_to_identify_s")
SAMPLING_KEYS = ("team_map_rms_c", "own_map_rms_c", "half_spread_s")


def summary_text(s: dict) -> str:
    lines = [
        f"Monte Carlo: {s['reported']} of {s['runs']} runs reported; outcomes "
        + (", ".join(f"{k} {v}" for k, v in s["outcomes"].items()) or "-")
    ]
    for seed, err in s["failed_runs"].items():
        lines.append(f"  seed {seed}: no report ({err})")
    for key, label, unit, scale, _bounds in METRICS:
        m = s["metrics"].get(key)
        if m is None:
            # a figure of another kind of mission is left out (a sampling run has no survey to cover)
            if s.get("sampling") and key not in SAMPLING_KEYS:
                continue
            if (key not in TEAM_KEYS or s.get("team")) and (key not in SAMPLING_KEYS or s.get("sampling")):
                lines.append(f"  {label:34s} -")
            continue
        u = f" {unit}" if unit else ""
        spread = f"range {m['min'] * scale:.3f}..{m['max'] * scale:.3f}"
        if m["lo"] is None:
            lines.append(f"  {label:34s} mean {m['mean'] * scale:8.3f}{u}  {m['too_few']}; {spread}{u}")
            continue
        cut = ", cut to the figure's range" if m.get("clipped") else ""
        lines.append(
            f"  {label:34s} mean {m['mean'] * scale:8.3f}{u}  95 % interval "
            f"[{m['lo'] * scale:.3f}, {m['hi'] * scale:.3f}]{u}  (n {m['n']}{cut}, {spread})"
        )
    return "\n".join(lines) + "\n"


def plot(runs: list[dict], s: dict, out: Path) -> list[Path]:
    """One panel per metric: each run a dot, the mean and its 95 % interval a bar."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    keys = [m for m in METRICS if m[0] in s["metrics"]]
    if not keys:
        return []
    fig, axes = plt.subplots(1, len(keys), figsize=(3 * len(keys), 3.2), squeeze=False)
    for ax, (key, label, unit, scale, _bounds) in zip(axes[0], keys):
        vals = [r["metrics"][key] * scale for r in runs if r.get("metrics") and r["metrics"].get(key) is not None]
        m = s["metrics"][key]
        ax.plot([0] * len(vals), vals, "o", alpha=0.6)
        if m["lo"] is None:  # too few runs: the mean alone
            ax.plot([0.3], [m["mean"] * scale], "s", color="k")
        else:
            ax.errorbar(
                [0.3],
                [m["mean"] * scale],
                yerr=[[(m["mean"] - m["lo"]) * scale], [(m["hi"] - m["mean"]) * scale]],
                fmt="s",
                color="k",
                capsize=4,
            )
        ax.set_xlim(-0.5, 0.8)
        ax.set_xticks([])
        ax.set_title(label, fontsize=8)
        ax.set_ylabel(unit)
    fig.suptitle(f"{s['reported']} runs: each run, mean and 95 % interval", fontsize=9)
    fig.tight_layout()
    paths = [out / "montecarlo.png", out / "montecarlo.svg"]
    for p in paths:
        fig.savefig(p)
    plt.close(fig)
    return paths

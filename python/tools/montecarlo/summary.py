"""Monte Carlo figures: per-run metrics from a mission report, and their
summary over the runs as mean and 95 % interval, as text, JSON and a plot.

The interval is the 95 % confidence interval of the mean (Student's t over
the runs): what a user needs to tell a change in their plan from noise."""

from __future__ import annotations

import math
from pathlib import Path

# (key, label, unit, scale to the unit)
METRICS = [
    ("coverage", "coverage once", "%", 100.0),
    ("pd", "PD (mine-like, covered area)", "", 1.0),
    ("false_alarms", "false alarms", "", 1.0),
    ("nav_error_rms_m", "nav error rms (mean of vehicles)", "m", 1.0),
    ("mission_time_s", "mission time", "min", 1 / 60),
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
    return {
        "coverage": cov.get("fraction_once"),
        "pd": pd,
        "false_alarms": det.get("false_alarms"),
        "nav_error_rms_m": sum(nav) / len(nav) if nav else None,
        "mission_time_s": rep.get("duration_s"),
        "outcome": rep.get("outcome"),
        "truth_samples_lost": sum(r["missing"] for r in rep.get("record", {}).values()),
    }


def interval(values: list[float]) -> dict:
    """Mean and 95 % confidence interval of the mean; with one value the interval is that value."""
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return {"n": n, "mean": mean, "lo": mean, "hi": mean, "min": mean, "max": mean}
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    half = (_T95[n - 2] if n - 1 <= len(_T95) else 1.96) * sd / math.sqrt(n)
    return {
        "n": n,
        "mean": mean,
        "lo": mean - half,
        "hi": mean + half,
        "min": min(values),
        "max": max(values),
        "sd": sd,
    }


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
    }
    for key, *_ in METRICS:
        vals = [r["metrics"][key] for r in ok if r["metrics"].get(key) is not None]
        if vals:
            out["metrics"][key] = interval([float(v) for v in vals])
    return out


def summary_text(s: dict) -> str:
    lines = [
        f"Monte Carlo: {s['reported']} of {s['runs']} runs reported; outcomes "
        + (", ".join(f"{k} {v}" for k, v in s["outcomes"].items()) or "-")
    ]
    for seed, err in s["failed_runs"].items():
        lines.append(f"  seed {seed}: no report ({err})")
    for key, label, unit, scale in METRICS:
        m = s["metrics"].get(key)
        if m is None:
            lines.append(f"  {label:34s} -")
            continue
        u = f" {unit}" if unit else ""
        lines.append(
            f"  {label:34s} mean {m['mean'] * scale:8.3f}{u}  95 % interval "
            f"[{m['lo'] * scale:.3f}, {m['hi'] * scale:.3f}]{u}  (n {m['n']}, "
            f"range {m['min'] * scale:.3f}..{m['max'] * scale:.3f})"
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
    for ax, (key, label, unit, scale) in zip(axes[0], keys):
        vals = [r["metrics"][key] * scale for r in runs if r.get("metrics") and r["metrics"].get(key) is not None]
        m = s["metrics"][key]
        ax.plot([0] * len(vals), vals, "o", alpha=0.6)
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

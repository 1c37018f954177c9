#!/usr/bin/env python3
"""Mission report from a run's log: text and JSON, and the plots.

    auv-report LOG [--survey survey.json] [--out DIR] [--radius 5] [--cell 2] [--no-plots]

Outcome and duration; area covered once and twice (tools/report/coverage.py);
probability of detection and false alarms, contacts (<V>.CONTACTS) against
the true target field (SIM.TARGETS) with an association radius; navigation
error (<V>.NAV against <V>.TRUTH). Writes report.txt, report.json and, unless
--no-plots, the plots (PNG and SVG) into --out (default: beside the log).

A damaged log is read past the damage (auvlcm.eventlog); what was skipped is
printed and kept in report.json ("log_damage"). Exit status: 0 done; 3 the
report was written but events were lost to damage; 2 usage error, no such
file, not an LCM log, or no vehicle in it.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from auvlcm.log import EXIT_EVENTS_LOST, damage_lines
from tools.report.association import associate
from tools.report.coverage import coverage_grid, point_in_polygon
from tools.report.run_data import RunData, interp_truth, load_run


def detection_stats(run: RunData, radius: float, covered=None) -> dict | None:
    """Each contact goes to the nearest true object within `radius`; a mine-like
    target is detected if any contact went to it; a contact near no object is a
    false alarm."""
    targets = run.targets()
    contacts = [(vid, c) for vid in run.vehicles for c in run.contacts(vid)]
    if not targets and not contacts:
        return None
    a = associate(targets, contacts, radius)
    tpos = np.array([(t.north_m, t.east_m) for t in targets]).reshape(-1, 2)
    mine, hit = a.mine, a.hit
    false_alarms = int(a.false_alarm.sum())
    on_clutter = int(sum(1 for k in a.nearest if k >= 0 and not mine[k]))
    per_vehicle = {vid: {"contacts": 0, "false_alarms": 0} for vid in run.vehicles}
    for (vid, _c), k in zip(contacts, a.nearest):
        per_vehicle[vid]["contacts"] += 1
        per_vehicle[vid]["false_alarms"] += int(k < 0)
    out = {
        "association_radius_m": radius,
        "mine_like_targets": int(mine.sum()),
        "clutter_objects": int((~mine).sum()),
        "contacts": len(contacts),
        "mine_like_detected": int((hit & mine).sum()),
        "pd": float((hit & mine).sum() / mine.sum()) if mine.any() else None,
        "contacts_on_clutter": on_clutter,
        "false_alarms": false_alarms,
        "per_vehicle": per_vehicle,
    }
    if covered is not None and len(tpos):
        inside = covered(tpos[:, 0], tpos[:, 1])
        m_in = mine & inside
        out["mine_like_in_covered_area"] = int(m_in.sum())
        out["pd_in_covered_area"] = float((hit & m_in).sum() / m_in.sum()) if m_in.any() else None
    return out


def nav_error(run: RunData) -> dict:
    out = {}
    for vid in run.vehicles:
        nav = run.nav(vid)
        if nav is None or not len(nav):
            continue
        tn, te = interp_truth(run, vid, nav.t)
        err = np.hypot(nav["north_m"] - tn, nav["east_m"] - te)
        out[vid] = {
            "mean_m": float(err.mean()),
            "rms_m": float(np.sqrt(np.mean(err**2))),
            "max_m": float(err.max()),
            "final_m": float(err[-1]),
            "samples": int(len(err)),
        }
    return out


def record_completeness(run: RunData) -> dict:
    """Ground-truth samples missing from the log, per vehicle: gaps in TRUTH
    longer than 1.5 of its usual interval. The simulator publishes TRUTH at a
    fixed rate, so each gap is messages the logger lost, or a stalled
    simulator; either way the figures above rest on less than was flown."""
    out = {}
    for vid in run.vehicles:
        t = np.asarray(run.truth(vid).t, float)
        if len(t) < 3:
            continue
        dt = np.diff(t)
        step = float(np.median(dt))
        gaps = dt[dt > 1.5 * step]
        missing = int(np.round(gaps / step).sum() - len(gaps)) if step > 0 else 0
        out[vid] = {
            "samples": int(len(t)),
            "missing": missing,
            "interval_s": step,
            "fraction_missing": missing / (len(t) + missing),
        }
    return out


def outcome_of(run: RunData) -> dict:
    if run.outcome is not None:
        vehicles = run.outcome.get("vehicles", {})
        return {
            "outcome": run.outcome.get("outcome"),
            "reason": run.outcome.get("reason", ""),
            "vehicle_outcomes": {k: v.get("outcome") for k, v in vehicles.items()},
            "vehicle_causes": {k: v.get("cause", "") for k, v in vehicles.items() if v.get("cause")},
        }
    per = {}
    for key, segs in run.timelines.items():
        vid, mgr = key.split(".", 1)
        if mgr == "NAVIGATOR" and segs:
            per[vid] = segs[-1].run
    return {"outcome": None, "reason": "no launcher end event in the log", "vehicle_outcomes": per}


def build_report(run: RunData, radius: float = 5.0, cell: float = 2.0) -> tuple[dict, object]:
    rep: dict = {
        "log": str(run.log.path),
        "vehicles": run.vehicles,
        **outcome_of(run),
        "duration_s": run.duration_s(),
        # the mission's events (RunData.mission_events); after its end only the launcher's notes of the stop
        "log_events": run.mission_events(),
        "log_events_after_end": (
            run.log.stats.events - run.log.events_to_mark if run.log.events_to_mark is not None else None
        ),
        "end_from": run.end_from,
        "undecodable_events": run.log.stats.undecodable,
        "log_damage": {
            "skipped_bytes": run.log.stats.damage.skipped_bytes,
            "lost_events": run.log.stats.damage.lost_events,
            "bad_channel_names": run.log.stats.damage.bad_channel_names,
        },
    }
    grid = None
    if run.survey:
        sv = run.survey
        grid = coverage_grid(run, sv["polygon"], sv["sonar"]["range_m"], sv["sonar"]["nadir_gap_m"], cell)
        total = float(np.count_nonzero(grid.inside)) * cell**2
        rep["coverage"] = {
            "survey_area_m2": sv["area_m2"],
            "raster_area_m2": total,
            "cell_m": cell,
            "covered_once_m2": grid.area_with(1),
            "covered_twice_m2": grid.area_with(2),
            "fraction_once": grid.area_with(1) / total if total else None,
            "fraction_twice": grid.area_with(2) / total if total else None,
        }

        def covered(n, e):
            i = ((n - grid.north0) / cell).astype(int)
            j = ((e - grid.east0) / cell).astype(int)
            ok = (i >= 0) & (i < grid.looks.shape[0]) & (j >= 0) & (j < grid.looks.shape[1])
            res = np.zeros(len(n), bool)
            res[ok] = grid.looks[i[ok], j[ok]] >= 1
            return res & point_in_polygon([tuple(p) for p in sv["polygon"]], n, e)

    rep["detection"] = detection_stats(run, radius, covered if grid is not None else None)
    rep["navigation_error"] = nav_error(run)
    rep["record"] = record_completeness(run)
    from tools.report.team_report import team_section

    team = team_section(run, radius)
    if team is not None:
        rep["team"] = team
    from tools.report.front_grade import sampling_section

    sampling = sampling_section(run)
    if sampling is not None:
        rep["sampling"] = sampling
    return rep, grid


def _fmt(x, unit="", scale=1.0, digits=1) -> str:
    return "-" if x is None else f"{x * scale:.{digits}f}{unit}"


def report_text(rep: dict) -> str:
    lines = [
        f"Mission report: {rep['log']}",
        f"outcome   {rep['outcome'] or '-'}" + (f" ({rep['reason']})" if rep.get("reason") else ""),
        f"duration  {rep['duration_s'] / 60:.1f} min sim time; {rep['log_events']} log events of the mission, "
        f"{rep['undecodable_events']} undecodable"
        + (
            f"; DAMAGED LOG: {rep['log_damage']['lost_events']} event(s) lost, "
            f"{rep['log_damage']['skipped_bytes']} byte(s) skipped"
            if rep["log_damage"]["skipped_bytes"]
            else ""
        ),
    ]
    for vid, o in rep["vehicle_outcomes"].items():
        cause = rep.get("vehicle_causes", {}).get(vid)
        lines.append(f"  {vid}: {o or 'unfinished'}" + (f" (cause: {cause})" if cause else ""))
    c = rep.get("coverage")
    if c:
        lines += [
            f"coverage  survey area {c['survey_area_m2'] / 1e6:.4f} km2 (raster {c['cell_m']:g} m cells)",
            f"  covered once  {c['covered_once_m2'] / 1e6:.4f} km2 ({_fmt(c['fraction_once'], ' %', 100)})",
            f"  covered twice {c['covered_twice_m2'] / 1e6:.4f} km2 ({_fmt(c['fraction_twice'], ' %', 100)})",
        ]
    else:
        lines.append("coverage  - (no survey geometry in the log or given)")
    d = rep.get("detection")
    if d:
        lines += [
            f"detection association radius {d['association_radius_m']:g} m",
            f"  mine-like targets {d['mine_like_targets']}, detected {d['mine_like_detected']}, "
            f"PD {_fmt(d['pd'], '', 1, 3)}"
            + (
                f"; in the covered area {d['mine_like_in_covered_area']}, PD {_fmt(d['pd_in_covered_area'], '', 1, 3)}"
                if "pd_in_covered_area" in d
                else ""
            ),
            f"  contacts {d['contacts']}: on clutter {d['contacts_on_clutter']}, false alarms {d['false_alarms']}",
        ]
    else:
        lines.append("detection - (no targets or contacts in the log)")
    lines.append("navigation error (NAV against TRUTH, horizontal)")
    for vid, e in rep["navigation_error"].items():
        lines.append(
            f"  {vid}: mean {e['mean_m']:.2f} m, rms {e['rms_m']:.2f} m, max {e['max_m']:.2f} m, "
            f"final {e['final_m']:.2f} m"
        )
    lines.append("record (TRUTH samples in the log; missing = lost by the logger or a stalled simulator)")
    for vid, r in rep.get("record", {}).items():
        lines.append(
            f"  {vid}: {r['samples']} samples every {r['interval_s']:g} s, {r['missing']} missing "
            f"({100 * r['fraction_missing']:.2f} %)"
        )
    if rep.get("team"):
        from tools.report.team_report import team_text

        lines += team_text(rep["team"])
    if rep.get("sampling"):
        from tools.report.front_grade import sampling_text

        lines += sampling_text(rep["sampling"])
    return "\n".join(lines) + "\n"


def survey_problem(sv) -> str:
    """Why a survey description (auv-plan-survey's survey.json) cannot be used; "" if it can."""
    try:
        poly = sv["polygon"]
        ok = len(poly) >= 3 and all(len(p) == 2 and all(math.isfinite(float(x)) for x in p) for p in poly)
        float(sv["area_m2"]), float(sv["sonar"]["range_m"]), float(sv["sonar"]["nadir_gap_m"])
    except (KeyError, TypeError, ValueError, IndexError) as exc:
        return f"not a survey description (auv-plan-survey's survey.json): {type(exc).__name__} {exc}"
    return "" if ok else "its polygon needs at least 3 finite 'north, east' vertices"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("log", type=Path)
    ap.add_argument("--survey", type=Path, help="survey.json (default: the one annotated in the log)")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--radius", type=float, default=5.0, help="contact-to-target association radius [m]")
    ap.add_argument("--cell", type=float, default=2.0, help="coverage grid cell [m]")
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args(argv)
    from tools.logs.lcmlog import not_a_log

    problem = not_a_log(args.log)
    if problem:
        print(f"report: {args.log}: {problem}", file=sys.stderr)
        return 2
    if args.radius <= 0 or args.cell <= 0 or not math.isfinite(args.radius + args.cell):
        print("report: --radius and --cell must be > 0", file=sys.stderr)
        return 2
    if args.survey is not None:
        try:
            problem = survey_problem(json.loads(args.survey.read_text()))
        except (OSError, ValueError) as exc:
            problem = getattr(exc, "strerror", None) or str(exc)
        if problem:
            print(f"report: --survey {args.survey}: {problem}", file=sys.stderr)
            return 2
    try:
        run = load_run(args.log, args.survey)
    except (OSError, ValueError) as exc:  # an unreadable log, a --survey that is not JSON
        print(f"report: {exc}", file=sys.stderr)
        return 2
    damage = damage_lines(args.log, run.log.stats)
    for line in damage:
        print(line, file=sys.stderr)
    if not run.vehicles:
        print(f"report: {args.log}: no vehicle ground truth (<V>.TRUTH) in the log", file=sys.stderr)
        return 2
    if run.survey is not None and (problem := survey_problem(run.survey)):
        print(
            f"report: {args.log}: the survey annotated in the log is unusable ({problem}): no coverage figures",
            file=sys.stderr,
        )
        run.survey = None
    out = args.out or args.log.parent
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        print(f"report: --out {out}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    rep, grid = build_report(run, args.radius, args.cell)
    if not args.no_plots:
        from tools.report.plots import make_plots

        plots = make_plots(run, grid, out)
        if rep.get("team"):
            from tools.report.team_plots import team_plots

            plots += team_plots(run, rep["team"], out)
        if rep.get("sampling"):
            from tools.report.sampling_plots import sampling_plots

            plots += sampling_plots(run, rep["sampling"], out)
        rep["plots"] = [str(p) for p in plots]
    (out / "report.json").write_text(json.dumps(rep, indent=2))
    text = report_text(rep)
    (out / "report.txt").write_text(text)
    print(text, end="")
    print(
        f"report: {out / 'report.txt'}, {out / 'report.json'}"
        + (f", {len(rep['plots'])} plot files" if "plots" in rep else "")
    )
    return EXIT_EVENTS_LOST if run.log.stats.events_lost else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("report: interrupted", file=sys.stderr)
        sys.exit(130)

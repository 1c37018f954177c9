#!/usr/bin/env python3
"""Plan a multi-vehicle sidescan survey: plans, a scenario and a summary.

    auv-plan-survey --polygon "0,0; 600,0; 600,400; 0,400" --vehicles 3 --heading 0 \\
        --range 40 --nadir-gap 4 --overlap 0.2 --out missions/scenarios/my_survey

Writes into --out: AUV<k>.chasm (each vehicle's navigator plan), <name>.yaml
(a scenario for auv-launch) and survey.json (the geometry: area,
shares, lines, operating area, for plots and reports). Polygon vertices are
"north,east" metres in the world's local frame. The plugins' limits are read
from the plugins (`chasm describe`, tools/plan/plugin_limits.py): the operating area
is bounded to what the `outside_area` test accepts, and every plan is checked
with `chasm check` before the scenario is written (docs/tools.md, "Limits").
Exit status 2 on bad input or a plan the plugins refuse.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shlex
import sys
from pathlib import Path

import yaml

from auvlcm.paths import ROOT, build_dir
from confcheck import rule_of
from sim import clock_modes
from tools.plan.plan_team import STATUS_RATE_HZ, add_team_options, vehicle_managers, write_team
from tools.plan.plan_text import Limits, estimated_duration_s, plan_text
from tools.plan.plugin_limits import LimitsError, check_plan, polygon_limits
from tools.plan.survey_geometry import GeometryError, format_polygon, parse_polygon
from tools.plan.survey_plan import Sonar, Survey, plan_survey
from tools.scenario.scenario_file import Manager

DEFAULTS = {
    "sim_config": ROOT / "missions" / "sim" / "remus100.yaml",
    "pilot_plan": ROOT / "missions" / "pilot" / "pilot.chasm",
    "pilot_bind": ROOT / "missions" / "bindings" / "pilot.bind",
    "nav_bind": ROOT / "missions" / "bindings" / "navigator.bind",
}


def survey_json(sv: Survey, ids: list[str], starts, lim: Limits) -> dict:
    return {
        "polygon": sv.polygon,
        "area_m2": sv.area_m2,
        "heading_deg": math.degrees(sv.heading_rad),
        "sonar": {"range_m": sv.sonar.range_m, "nadir_gap_m": sv.sonar.nadir_gap_m},
        "overlap": sv.overlap,
        "spacing_m": sv.spacing_m,
        "margin_m": sv.margin_m,
        "operating_area": sv.operating_area,
        "vehicles": {
            vid: {
                "area_m2": v.area_m2,
                "polygon": v.polygon,
                "start": list(st),
                "estimated_duration_s": estimated_duration_s(v, st, lim),
                "length_m": v.length_m(),
                "legs": [{"kind": leg.kind, "line": leg.line, "start": leg.start, "end": leg.end} for leg in v.legs],
            }
            for vid, v, st in zip(ids, sv.vehicles, starts)
        },
    }


def auto_starts(sv: Survey, back_m: float = 30.0) -> list[tuple[float, float]]:
    """A launch point behind each vehicle's first line, on its extension."""
    out = []
    for v in sv.vehicles:
        leg = v.legs[0]
        d = math.dist(leg.start, leg.end) or 1.0
        out.append(
            (
                leg.start[0] - back_m * (leg.end[0] - leg.start[0]) / d,
                leg.start[1] - back_m * (leg.end[1] - leg.start[1]) / d,
            )
        )
    return out


def _rel(p: Path, base: Path) -> str:
    return os.path.relpath(p, base)


def scenario_dict(name: str, out: Path, ids, sv: Survey, starts, args, lim: Limits) -> dict:
    longest = max(estimated_duration_s(v, st, lim) for v, st in zip(sv.vehicles, starts))
    vehicles = []
    for vid, v, st in zip(ids, sv.vehicles, starts):
        leg = v.legs[0]
        heading = math.atan2(leg.start[1] - st[1], leg.start[0] - st[0]) % (2 * math.pi)
        vehicles.append(
            {
                "id": vid,
                "sim": {
                    "config": _rel(args.sim_config, out),
                    "initial": {
                        "north_m": round(st[0], 1),
                        "east_m": round(st[1], 1),
                        "heading_rad": round(heading, 4),
                    },
                },
                **({"nav": args.nav} if args.nav != "ins" else {}),
                "managers": vehicle_managers(args, out, f"{vid}.chasm", args.nav_bind),
            }
        )
    world = read_world(args.world) if args.world else {}
    return {
        "name": name,
        "seed": args.seed,
        "world": world or {},
        "time": {"mode": clock_modes.LOCKSTEP, "limit": round(1.5 * longest + 900)},
        "vehicles": vehicles,
    }


def read_world(path: Path) -> dict:
    """The --world file, read and checked like every configuration (confcheck)."""
    from confcheck import Checker

    c = Checker.from_file(path)
    world = c.plain(c.root)
    c.raise_errors()
    return world if isinstance(world, dict) else {}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--polygon", required=True, help='"n,e; n,e; ..." in metres, or @FILE holding that text')
    ap.add_argument("--vehicles", type=int, default=1)
    ap.add_argument("--heading", type=float, default=0.0, help="line heading [deg from north]")
    ap.add_argument("--range", type=float, required=True, help="sonar ground range per side [m]")
    ap.add_argument("--nadir-gap", type=float, default=0.0, help="blind half-width under the track [m]")
    ap.add_argument("--overlap", type=float, default=0.1, help="fraction of the full spacing given up, [0, 1)")
    ap.add_argument("--run-in", type=float, default=20.0, help="line extension before and after the area [m]")
    ap.add_argument("--margin", type=float, help="operating area beyond the legs [m] (default: range + 50)")
    ap.add_argument("--starts", help='launch points "n,e; n,e; ..." (default: 30 m behind each first line)')
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--name", help="scenario name (default: the --out folder's name)")
    ap.add_argument("--ids", help="vehicle ids, comma-separated (default AUV1, AUV2, ...)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--world", type=Path, help="YAML file: the scenario's world section")
    ap.add_argument(
        "--status-rate",
        type=float,
        default=STATUS_RATE_HZ,
        help="managers' status messages per second of mission time, besides one on every change; "
        f"0: every cycle (default {STATUS_RATE_HZ:g})",
    )
    ap.add_argument(
        "--nav",
        choices=("ins", "ekf"),
        default="ins",
        help="what each vehicle steers by: the simulator's INS, or the onboard filter auv-nav",
    )
    ap.add_argument(
        "--build",
        type=Path,
        default=build_dir(),
        help="build folder whose plugins set the limits and check the plans (default: the repository's)",
    )
    add_team_options(ap)
    lim = Limits()
    for key, default in vars(lim).items():
        ap.add_argument("--" + key.replace("_", "-"), type=float, default=default)
    for key, default in DEFAULTS.items():
        ap.add_argument("--" + key.replace("_", "-"), type=Path, default=default)
    args = ap.parse_args(argv)
    lim = Limits(**{k: getattr(args, k) for k in vars(lim)})
    if args.backseat and args.team is None:
        print(
            "plan_survey: --backseat: with --team only (a plain survey's GPS fixes surface by pitch, "
            "which a frontseat does not take)",
            file=sys.stderr,
        )
        return 2
    if args.team is not None:
        if not 1 <= args.team <= 15 - args.ri:
            print(
                f"plan_survey: --team {args.team}: 1 to {15 - args.ri} search vehicles "
                "(the team link numbers 16 vehicles, 0..15)",
                file=sys.stderr,
            )
            return 2
        bad = [
            f"--{k.replace('_', '-')} {getattr(args, k):g}"
            for k, ok in (
                ("slot_guard", args.slot_guard >= 0),
                ("silent", args.silent > 0),
                ("linger", args.linger >= 0),
                ("ri_back", math.isfinite(args.ri_back)),
            )
            if not (ok and math.isfinite(getattr(args, k)))
        ]
        if bad:
            print(f"plan_survey: {', '.join(bad)}: out of range (guard, linger >= 0 s, silent > 0 s)", file=sys.stderr)
            return 2
        args.vehicles = args.team
    problem = rule_of(Manager, "status_rate_hz").problem(args.status_rate)  # what the launcher takes
    if problem:
        print(f"plan_survey: --status-rate {args.status_rate:g}: out of range ({problem})", file=sys.stderr)
        return 2
    try:
        text = Path(args.polygon[1:]).read_text() if args.polygon.startswith("@") else args.polygon
        polygon = parse_polygon(text)
        ids = args.ids.split(",") if args.ids else [f"AUV{k + 1}" for k in range(args.vehicles)]
        if len(ids) != args.vehicles:
            raise GeometryError(f"--ids names {len(ids)} vehicles, --vehicles says {args.vehicles}")
        starts = parse_polygon_points(args.starts, args.vehicles) if args.starts else None
        if args.world:
            read_world(args.world)  # refused here, before anything is written
        area_limits = polygon_limits(args.build)
        sv = plan_survey(
            polygon,
            args.vehicles,
            math.radians(args.heading),
            Sonar(args.range, args.nadir_gap),
            args.overlap,
            args.run_in,
            args.margin,
            starts,
            area_limits.max_vertices,
        )
        if len(format_polygon(sv.operating_area)) > area_limits.max_chars:
            raise GeometryError(
                f"the operating area's text is longer than the {area_limits.max_chars} characters outside_area accepts"
            )
        for k, v in enumerate(sv.vehicles):
            if not v.legs:
                raise GeometryError(f"vehicle {k + 1} got no lines")
    except (GeometryError, LimitsError, OSError, ValueError) as exc:  # ValueError: ConfigError of --world
        print(f"plan_survey: {exc}", file=sys.stderr)
        return 2
    starts = starts or auto_starts(sv)
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    name = args.name or out.name
    errors, refused = [], 0
    team = None
    if args.team is not None:
        try:
            team, paths = write_team(sv, ids, starts, args, lim, out)
        except (GeometryError, OSError, ValueError) as exc:  # ValueError: a sim config's ConfigError
            print(f"plan_survey: {exc}", file=sys.stderr)
            return 2
        if (args.build / "plugins" / "chasm_team.so").is_file():
            for path in paths:
                problems = check_plan(path, args.build)
                refused += bool(problems)
                errors += problems
        else:
            print(
                f"plan_survey: no team plugin in {args.build}/plugins: the team plans are not "
                "checked (they load once the team plugin is built)",
                file=sys.stderr,
            )
    else:
        for vid, v, st in zip(ids, sv.vehicles, starts):
            path = out / f"{vid}.chasm"
            path.write_text(plan_text(sv, v, vid, st, lim, path))
            problems = check_plan(path, args.build)  # what the launcher would refuse, refused now
            refused += bool(problems)
            errors += problems
    if errors:
        print("\n".join(errors), file=sys.stderr)
        print(
            f"plan_survey: {refused} plan(s) do not load with the plugins of {args.build}; no scenario written",
            file=sys.stderr,
        )
        return 2
    geometry = survey_json(sv, ids, starts, lim)
    sc = scenario_dict(name, out, ids, sv, starts, args, lim)
    if team is not None:
        geometry["team"] = team["team"]
        sc["time"], sc["vehicles"] = team["time"], team["vehicles"]
        ids = team["team"]["roster"]
    (out / "survey.json").write_text(json.dumps(geometry, indent=1))
    sc["survey"] = "survey.json"
    command = " ".join(
        shlex.quote(_rel(Path(a).resolve(), ROOT) if "/" in a and Path(a).exists() else a)
        for a in (argv if argv is not None else sys.argv[1:])
    )
    (out / f"{name}.yaml").write_text(
        f"# Written by auv-plan-survey (python/tools/plan/plan_survey.py); polygon {format_polygon(polygon)}\n"
        f"# Regenerate (from the repository root): .venv/bin/auv-plan-survey {command}\n"
        + yaml.safe_dump(sc, sort_keys=False)
    )
    print(
        f"plan_survey: {sv.area_m2 / 1e6:.3f} km2 in {len(sv.vehicles)} shares, lines {sv.spacing_m:.1f} m apart "
        f"(tolerates {sv.margin_m:.1f} m off track)"
    )
    if team is not None:
        t = team["team"]
        clock = (
            f"{', '.join(t['backseat'])} from the backseat, scaled clock x{args.warp:g} from the simulators"
            if t.get("backseat")
            else f"lockstep clock from the {args.time_source}"
        )
        print(
            f"  team {','.join(t['roster'])}: TDMA {t['slots']} slots of {t['slot_s']:g} s "
            f"({t['frame_bytes']} B frames of {t['frame_s']:g} s), {clock}"
        )
    for vid, v, st in zip(ids, sv.vehicles, starts):
        print(
            f"  {vid}: {v.area_m2 / 1e6:.4f} km2, {len(v.lines)} line legs, {v.length_m() / 1000:.2f} km, "
            f"about {estimated_duration_s(v, st, lim) / 60:.0f} min"
        )
    print(f"wrote {out}/: {', '.join(f'{i}.chasm' for i in ids)}, {name}.yaml, survey.json")
    return 0


def parse_polygon_points(text: str, n: int) -> list[tuple[float, float]]:
    pts = []
    for part in (p for p in text.split(";") if p.strip()):
        try:
            a, b = (float(x) for x in part.split(","))
        except ValueError:
            raise GeometryError(f"--starts: '{part.strip()}' is not 'north,east'") from None
        pts.append((a, b))
    if len(pts) != n:
        raise GeometryError(f"--starts gives {len(pts)} points for {n} vehicles")
    return pts


if __name__ == "__main__":
    sys.exit(main())

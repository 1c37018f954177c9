"""The team scenario of auv-plan-survey --team N: N search vehicles and an RI vehicle.

    auv-plan-survey --polygon "20,20; 220,20; 220,200; 20,200" --team 3 --ri 1 \\
        --range 40 --nadir-gap 8 --out missions/scenarios/mcm_team

The search vehicles split the area like a plain survey (their lines become
the team's `lines` string); the RI vehicle starts between the two middle
search vehicles' launch points, `--ri-back` metres further back. The TDMA
slot is computed from the modem of the search vehicles' simulator configuration (frame duration = frame_overhead_s + 8 max_frame_bytes
/ bitrate_bps) plus the largest propagation delay across the operating area
(its diameter at 1 400 m/s, slower than any sea water) plus a guard. Time:
`--time lockstep` (default; multi-HIL lockstep, every simulator and manager
finishes each step: reruns are identical) or `fast` (the launcher's clock).
docs/missions.md, "Team mission".

`--backseat AUV1,AUV2` flies those vehicles from their backseat (docs/frontseat.md,
"The team in backseat mode"): their simulator configuration gets the simulator's
Iver3 frontseat (`frontseat:`, its own mission: the launch heading at the survey
depth and speed), their managers no PILOT (auv-launch starts auv-frontseat in its
place), their plans surface by asking for 0 m; a frontseat is a device on a port,
which cannot take part in a lockstep world, so the whole world then runs on the
simulators' scaled clock (multi-HIL, `--warp`).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

from auvlcm.paths import ROOT
from sim import clock_modes
from tools.plan.plan_text import Limits, estimated_duration_s
from tools.plan.survey_geometry import GeometryError
from tools.plan.survey_plan import Survey
from tools.plan.team_plan_text import TeamLink, lines_string, ri_plan, search_plan
from tools.scenario.scenario_file import CLOCK_SOURCES

SLOWEST_SOUND_MPS = 1400.0  # below any sea water's: the delay bound stays a bound
MAX_PARAM_STRING = 1023  # the plan language's longest string (docs/chasm.md, "Limits")

TEAM_DEFAULTS = {
    "search_config": ROOT / "missions" / "sim" / "remus100_team_search.yaml",
    "ri_config": ROOT / "missions" / "sim" / "remus100_ri.yaml",
    "team_bind": ROOT / "missions" / "bindings" / "team_search.bind",
    "ri_bind": ROOT / "missions" / "bindings" / "team_ri.bind",
}


# Status messages per second of mission time of the managers a planner writes
# (and one at once on every change): an operator's display needs no more, and
# at every cycle they were a tenth of a fleet's LCM traffic (docs/performance.md).
STATUS_RATE_HZ = 2.0


def vehicle_managers(args, out: Path, nav_plan: str, nav_bind: Path, backseat: bool = False) -> list[dict]:
    """A vehicle's PILOT (20 Hz) and NAVIGATOR (10 Hz) as a scenario lists them; a
    backseat vehicle's NAVIGATOR alone (auv-frontseat stands where the PILOT stands)."""
    status = {"status_rate": args.status_rate}
    pilot = {"name": "PILOT", "plan": _rel(args.pilot_plan, out), "bind": _rel(args.pilot_bind, out), "rate": 20}
    return [
        *([] if backseat else [{**pilot, **status}]),
        {"name": "NAVIGATOR", "plan": nav_plan, "bind": _rel(nav_bind, out), "rate": 10, **status},
    ]


def parse_backseat(text: str | None, roster: list[str]) -> set[str]:
    """--backseat: vehicle ids of the roster, comma-separated, or `all` (GeometryError if not)."""
    if not text:
        return set()
    ids = roster if text.strip() == "all" else [i.strip() for i in text.split(",") if i.strip()]
    unknown = [i for i in ids if i not in roster]
    if unknown or not ids:
        raise GeometryError(
            f"--backseat {text}: {', '.join(unknown) or 'no vehicle'}: not of the team {','.join(roster)}"
        )
    return set(ids)


def frontseat_section(vid: str, heading_rad: float, lim: Limits) -> dict:
    """The simulator's Iver3 frontseat of a backseat vehicle (python/sim/frontseat.py):
    granted the backseat's requests from 1 m down; its own mission (before the first
    grant, and whenever it takes the vehicle back) the launch heading at the survey
    depth and speed; on a pty in the run folder (beside the merged configuration)."""
    return {
        "control_min_depth_m": 1.0,
        "mission_heading_deg": round(math.degrees(heading_rad) % 360.0, 1) % 360.0,
        "mission_depth_m": lim.depth_m if lim.depth_m > 0 else 3.0,
        "mission_speed_mps": lim.speed_mps,
        "wire": {"protocol": "iver3", "pty": f"{vid}.frontseat", "baud": 19200},
    }


def add_team_options(ap) -> None:
    g = ap.add_argument_group('team scenario (docs/missions.md, "Team mission")')
    g.add_argument(
        "--team",
        type=int,
        metavar="N_SEARCH",
        help="write a cooperative MCM team scenario with N search vehicles (ignores --vehicles)",
    )
    g.add_argument("--ri", type=int, default=1, choices=(0, 1), help="reacquire-identify vehicles (0 or 1)")
    g.add_argument(
        "--ri-start", help='the RI vehicle\'s launch point "n,e" (default: behind the middle search vehicles)'
    )
    g.add_argument(
        "--ri-back",
        type=float,
        default=20.0,
        help="default RI start: this far behind the middle search vehicles' launch points [m]",
    )
    g.add_argument("--slot-guard", type=float, default=0.3, help="TDMA guard time added to each slot [s]")
    g.add_argument("--silent", type=float, default=120.0, help="a teammate unheard this long is lost [s]")
    g.add_argument("--linger", type=float, default=120.0, help="search: on the link after the lines [s]")
    g.add_argument(
        "--time-source",
        choices=CLOCK_SOURCES,
        default="simulators",
        help="whose lockstep clock: the simulators' multi-HIL nodes (default) or the launcher's",
    )
    g.add_argument(
        "--backseat",
        metavar="IDS",
        help="fly these vehicles (comma-separated, or `all`) from their backseat: the simulator's Iver3 "
        "frontseat, auv-frontseat for the PILOT; the world then runs scaled (docs/frontseat.md)",
    )
    g.add_argument("--warp", type=float, default=4.0, help="with --backseat: the simulators' scaled clock (default 4)")
    for key, default in TEAM_DEFAULTS.items():
        g.add_argument("--" + key.replace("_", "-"), type=Path, default=default)


@dataclass
class Modem:
    frame_bytes: int
    frame_s: float


def modem_of(config: Path) -> Modem:
    """The modem of a simulator configuration (errors as file:line:col: ConfigError)."""
    from sim.config import load

    cfg = load(config)
    if cfg.modem is None:
        raise GeometryError(f"{config}: no modem: section (a team needs the acoustic modem)")
    m = cfg.modem
    return Modem(m.max_frame_bytes, m.frame_overhead_s + 8.0 * m.max_frame_bytes / m.bitrate_bps)


def slot_length(modem: Modem, area, guard_s: float) -> float:
    """Frame duration + the largest propagation delay across the area + guard, up to 0.1 s."""
    diameter = max(math.dist(a, b) for a in area for b in area)
    return math.ceil((modem.frame_s + diameter / SLOWEST_SOUND_MPS + guard_s) * 10 - 1e-9) / 10


def ri_start_of(sv: Survey, starts, args) -> tuple[float, float]:
    """--ri-start, or between the two middle search vehicles' launch points (apart from
    both), --ri-back further back along the run-in to the first line."""
    if args.ri_start:
        try:
            n, e = (float(x) for x in args.ri_start.split(","))
        except ValueError:
            raise GeometryError(f"--ri-start: '{args.ri_start}' is not 'north,east'") from None
        return n, e
    k = len(starts) // 2
    a, b = (starts[k - 1], starts[k]) if len(starts) >= 2 else (starts[0], starts[0])
    first = sv.vehicles[0].legs[0].start
    d = math.dist(first, starts[0]) or 1.0
    un, ue = (first[0] - starts[0][0]) / d, (first[1] - starts[0][1]) / d
    mid = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
    back = args.ri_back if len(starts) >= 2 else args.ri_back + 30.0
    return round(mid[0] - back * un, 1), round(mid[1] - back * ue, 1)


def write_team(sv: Survey, ids: list[str], starts, args, lim: Limits, out: Path) -> tuple[dict, list[Path]]:
    """Plans into `out`; the scenario dict (without header) and the plan paths."""
    for key in ("search_config", "ri_config"):
        path = getattr(args, key)
        if not path.is_file():
            raise GeometryError(f"--{key.replace('_', '-')} {path}: no such file")
    modem = modem_of(args.search_config)
    ri_ids = [f"AUV{len(ids) + 1}"] if args.ri else []
    roster = ids + ri_ids
    backseat = parse_backseat(args.backseat, roster)
    if backseat and args.time_source != "simulators":
        raise GeometryError(
            "--backseat: a frontseat is a device on a port, which cannot take part in the launcher's lockstep "
            "clock: leave --time-source at simulators (the world then runs on their scaled clock)"
        )
    if backseat and not (0 < args.warp <= 100):
        raise GeometryError(f"--warp {args.warp:g}: a scaled clock's warp is in (0, 100]")
    if ri_ids:
        ri_modem = modem_of(args.ri_config)
        if (ri_modem.frame_bytes, round(ri_modem.frame_s, 6)) != (modem.frame_bytes, round(modem.frame_s, 6)):
            raise GeometryError(
                f"{args.ri_config}: its modem's frames ({ri_modem.frame_bytes} B, "
                f"{ri_modem.frame_s:g} s) differ from the search vehicles' "
                f"({modem.frame_bytes} B, {modem.frame_s:g} s): one team, one modem profile"
            )
    shares = [[(leg.start, leg.end) for leg in v.lines] for v in sv.vehicles]
    lines = lines_string(shares)
    if len(lines) > MAX_PARAM_STRING:
        raise GeometryError(
            f"the team's lines string is {len(lines)} characters, over the plan language's "
            f"{MAX_PARAM_STRING}: fewer lines (wider --range or a smaller area)"
        )
    link = TeamLink(
        roster, lines, slot_length(modem, sv.operating_area, args.slot_guard), modem.frame_bytes, silent_s=args.silent
    )
    longest = max(estimated_duration_s(v, st, lim) for v, st in zip(sv.vehicles, starts))
    # after its own lines a search vehicle may take over a lost teammate's: time for both
    timeout = lim.timeout_s or 2.5 * longest + args.linger + 600
    paths = []
    for vid, v, st in zip(ids, sv.vehicles, starts):
        path = out / f"{vid}.chasm"
        summary = (
            f"Share {v.index + 1} of {len(ids)}: {len(v.lines)} lines, {v.length_m() / 1000:.2f} km, "
            f"about {estimated_duration_s(v, st, lim) / 60:.0f} min before any takeover."
        )
        path.write_text(
            search_plan(
                vid,
                link,
                lim,
                timeout,
                sv.operating_area,
                path,
                v.legs[0].start,
                v.legs[-1].end,
                summary,
                args.linger,
                vid in backseat,
            )
        )
        paths.append(path)
    ri_st = ri_start_of(sv, starts, args)
    for vid in ri_ids:
        path = out / f"{vid}.chasm"
        path.write_text(
            ri_plan(
                vid,
                link,
                lim,
                timeout,
                sv.operating_area,
                path,
                f"Starts at {ri_st[0]:.1f}, {ri_st[1]:.1f}; identifies what the search reports.",
                vid in backseat,
            )
        )
        paths.append(path)
    vehicles = []
    # lockstep: every simulator, pilot and navigator, and each onboard filter (--nav ekf)
    participants = (4 if args.nav == "ekf" else 3) * len(roster)
    for vid, st, first in [(i, s, v.legs[0].start) for i, s, v in zip(ids, starts, sv.vehicles)] + [
        (i, ri_st, (ri_st[0] + 1.0, ri_st[1])) for i in ri_ids
    ]:
        heading = math.atan2(first[1] - st[1], first[0] - st[0]) % (2 * math.pi)
        sim = {
            "config": _rel(args.ri_config if vid in ri_ids else args.search_config, out),
            "initial": {"north_m": round(st[0], 1), "east_m": round(st[1], 1), "heading_rad": round(heading, 4)},
        }
        if backseat:  # one world on the simulators' scaled clock; the first vehicle serves it
            sim["simulation"] = {"clock": "scaled", "warp": args.warp}
            sim["multihil"] = {"enabled": True, "priority": 10 * (len(roster) - len(vehicles))}
        elif args.time_source == "simulators":
            sim["simulation"] = {"clock": "lockstep"}
            sim["multihil"] = {"enabled": True, "lockstep_participants": participants}
        if vid in backseat:
            sim["frontseat"] = frontseat_section(vid, heading, lim)
        vehicles.append(
            {
                "id": vid,
                "sim": sim,
                # a backseat vehicle's NAV is its frontseat's
                **({"nav": args.nav} if args.nav != "ins" and vid not in backseat else {}),
                **({"backseat": {"max_depth": lim.max_depth_m}} if vid in backseat else {}),
                "managers": vehicle_managers(
                    args, out, f"{vid}.chasm", args.ri_bind if vid in ri_ids else args.team_bind, vid in backseat
                ),
            }
        )
    limit = round(timeout + 120)
    if backseat:
        time = {"mode": clock_modes.SCALED, "warp": args.warp, "source": args.time_source, "limit": limit}
    else:
        time = {"mode": clock_modes.LOCKSTEP, "source": args.time_source, "limit": limit}
    team = {
        "roster": roster,
        "search": ids,
        "ri": ri_ids,
        "slot_s": link.slot_s,
        "slots": len(roster),
        "frame_bytes": modem.frame_bytes,
        "frame_s": round(modem.frame_s, 3),
        "lines": lines,
        **({"backseat": sorted(backseat)} if backseat else {}),
    }
    return {"time": time, "vehicles": vehicles, "team": team}, paths


def _rel(p: Path, base: Path) -> str:
    return os.path.relpath(Path(p).resolve(), base)

"""Write the navigator plans of a cooperative MCM team (docs/missions.md, "Team mission").

Every plan `use team` (the team plugin, c/plugins/team/, TEAM_SPEC section 4)
with the same roster (`team`) and the same line list (`lines`: owner index,
then from and to of each survey line of the whole team), and its own TDMA
slot. A search vehicle flies its lines and then any it takes over
(`team_survey`), reports its mine-like contacts (`search_contacts`), then
lingers on the link for `linger` so its last reports get acknowledged, and
surfaces. The reacquire-identify (RI) vehicle flies through the reported
targets (`ri_reacquire`) until the search is over and its queue is empty.
The behaviors' tuning is in `param`s at the top of each plan so a user can
adjust it without rerunning the planner. A vehicle flown from its backseat
(auv-plan-survey --backseat, docs/frontseat.md) gets the same plan, surfacing by
asking its frontseat for 0 m (`surface_speed`) and riding out a frontseat's
silence for BACKSEAT_NAV_TIMEOUT_S (its NAV is the frontseat's).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, replace
from pathlib import Path

from tools.plan.plan_text import NAVIGATOR_IO, TEAM_SAFETY, Limits
from tools.plan.survey_geometry import format_polygon


@dataclass
class TeamLink:
    roster: list[str]  # team index = position in this list
    lines: str  # TEAM_SPEC section 4 format
    slot_s: float  # TDMA slot length
    frame_bytes: int
    silent_s: float = 120.0  # a teammate unheard this long is lost
    repeat: int = 3  # unacked contact reports: sent at most this many times per cycle round
    status_every_s: float = 20.0


# Every team plan ends its mission state the same way: up to the surface.
_RECOVER = ["    state recover {", "        do surface()", "    }", "}"]
# ... a backseat's by asking its frontseat for 0 m (it takes no pitch or rpm: docs/frontseat.md)
_RECOVER_BACKSEAT = ["    state recover {", "        do surface(speed = $surface_speed)", "    }", "}"]


def _recover(backseat: bool) -> list[str]:
    return _RECOVER_BACKSEAT if backseat else _RECOVER


# A backseat's NAV is its frontseat's, published at each of its answers: NAV's age is the
# frontseat's silence, which the frontseat rides out on its own (the last request until its
# timeout, then its own mission), not an emergency the shared rules abort for at once.
BACKSEAT_NAV_TIMEOUT_S = 15.0


def _backseat(lim: Limits, backseat: bool) -> Limits:
    """The limits a backseat plan is written with: NAV older than BACKSEAT_NAV_TIMEOUT_S
    at least before the shared rules abort."""
    return replace(lim, nav_timeout_s=max(lim.nav_timeout_s, BACKSEAT_NAV_TIMEOUT_S)) if backseat else lim


def _backseat_params(lim: Limits) -> list[str]:
    """A plan flown from the backseat surfaces (recover, emergency) by asking for 0 m."""
    return [
        "",
        "# Flown from the backseat (docs/frontseat.md): the frontseat holds depths and speeds",
        "# only, so the way up (recover, the safety rules' emergency) asks it for 0 m at this speed;",
        "# NAV is the frontseat's (nav_timeout above: its silence is ridden out, not aborted for).",
        f"param surface_speed = {lim.speed_mps:g} m/s",
    ]


def lines_string(shares: list[list[tuple[tuple[float, float], tuple[float, float]]]]) -> str:
    """`"0: n,e n,e; 0: ...; 1: ..."`: each vehicle's lines in flying order, owner index first."""
    parts = []
    for owner, lines in enumerate(shares):
        for a, b in lines:
            parts.append(f"{owner}: {a[0]:.1f},{a[1]:.1f} {b[0]:.1f},{b[1]:.1f}")
    return "; ".join(parts)


def _header(
    vid: str, role: str, link: TeamLink, lim: Limits, timeout_s: float, area, plan_path: Path, extra: list[str]
) -> list[str]:
    me = link.roster.index(vid)
    return [
        f"# {vid}: {role} of the team {','.join(link.roster)}, written by",
        "# auv-plan-survey --team (re-run it rather than edit this file;",
        "# the tuning params below are safe to adjust by hand).",
        *extra,
        f'mission "{vid} team {role}"',
        "",
        f'include "{os.path.relpath(NAVIGATOR_IO, plan_path.parent)}"',
        "use guidance",
        "use team",
        "",
        "# The team: the same roster and lines in every vehicle's plan (index = codec number).",
        f'param team        = "{",".join(link.roster)}"',
        f'param me          = "{vid}"',
        f'param lines       = "{link.lines}"',
        f"param slot        = {link.slot_s:g} s      # TDMA: frame duration + largest propagation delay + guard",
        f"param slots       = {len(link.roster)}",
        f"param my_slot     = {me}",
        f"param frame_bytes = {link.frame_bytes}",
        f"param silent      = {link.silent_s:g} s",
        f"param repeat      = {link.repeat}",
        f"param speed       = {lim.speed_mps:g} m/s",
        f"param depth       = {lim.depth_m:g} m",
        "",
        "# Limits of the shared safety rules (included at the end).",
        f"param max_depth       = {lim.max_depth_m:g} m",
        f"param min_altitude    = {lim.min_altitude_m:g} m",
        f"param nav_timeout     = {lim.nav_timeout_s:g} s",
        f"param mission_timeout = {timeout_s / 60:.0f} min",
        f'param area            = "{format_polygon(area)}"',
        "",
        "# Whole messages (team bindings: missions/bindings/team_*.bind).",
        "input  modem_rx    : messages",
        "output modem_tx    : messages",
        "output team_events : messages",
    ]


def _link_actions(link: TeamLink) -> list[str]:
    return [
        "    do team_link(team = $team, me = $me, slot = $slot, slots = $slots, my_slot = $my_slot, "
        "frame_bytes = $frame_bytes, rx = modem_rx, tx = modem_tx, events = team_events, "
        "silent = $silent, repeat = $repeat)",
        f"    do team_status() every {link.status_every_s:g} s",
        "    do keep_clear(radius = 30 m, band = 3 m, horizon = 30 s)",
    ]


def _footer(plan_path: Path) -> list[str]:
    return ["", f'include "{os.path.relpath(TEAM_SAFETY, plan_path.parent)}"', ""]


def search_plan(
    vid: str,
    link: TeamLink,
    lim: Limits,
    timeout_s: float,
    area,
    plan_path: Path,
    start,
    end,
    summary: str,
    linger_s: float = 120.0,
    backseat: bool = False,
) -> str:
    lim = _backseat(lim, backseat)
    out = _header(vid, "search", link, lim, timeout_s, area, plan_path, [f"# {summary}"])
    out += _backseat_params(lim) if backseat else []
    out += [
        "input  contacts    : messages(256)",
        "",
        "param min_score = 0.5           # a merged contact scoring this or more is mine-like: reported",
        "param merge     = 5 m           # looks closer than this are one object",
        f"param linger    = {linger_s:g} s         # on the link after the lines: the last reports get acked",
        "",
        "start mission",
        "",
        "# The link, the status and the deconfliction run in `mission`, over every child.",
        "state mission {",
        *_link_actions(link),
        "    do search_contacts(rx = contacts, min_score = $min_score, merge = $merge)",
        "    state dive {",
        f"        do goto(north = {start[0]:.1f} m, east = {start[1]:.1f} m, speed = $speed)",
        "        do hold_depth(depth = $depth)",
        "        next survey",
        "    }",
        "    state survey {",
        "        do team_survey(lines = $lines, speed = $speed, depth = $depth)",
        "        next linger",
        "    }",
        "    state linger {",
        f"        do loiter(north = {end[0]:.1f} m, east = {end[1]:.1f} m, radius = 20 m, speed = $speed)",
        "        do hold_depth(depth = $depth)",
        "        test lingered : elapsed > $linger",
        "        when lingered -> recover",
        "    }",
        *_recover(backseat),
    ]
    return "\n".join(out + _footer(plan_path))


def ri_plan(
    vid: str,
    link: TeamLink,
    lim: Limits,
    timeout_s: float,
    area,
    plan_path: Path,
    summary: str,
    backseat: bool = False,
) -> str:
    lim = _backseat(lim, backseat)
    out = _header(vid, "reacquire-identify", link, lim, timeout_s, area, plan_path, [f"# {summary}"])
    out += _backseat_params(lim) if backseat else []
    out += [
        "input  looks       : messages(256)",
        "",
        "param merge        = 5 m        # reports closer than this are one target",
        "param look_gate    = 10 m       # a target's first look counts this far from the reports",
        "param ident_range  = 6 m        # the sensor's range: reached within it, passes run on this far",
        "param look_timeout = 180 s      # at a target this long undecided: not found",
        "param ident_error  = 0.001      # a target is called once its looks leave this chance of a wrong call",
        "param runout       = 30 m       # straight on past a target before turning back (> turning circle)",
        "",
        "start mission",
        "",
        "state mission {",
        *_link_actions(link),
        "    state reacquire {",
        "        do ri_reacquire(looks = looks, merge = $merge, look_gate = $look_gate, ident_range = $ident_range, "
        "look_timeout = $look_timeout, ident_error = $ident_error, runout = $runout, speed = $speed, depth = $depth)",
        "        next recover",
        "    }",
        *_recover(backseat),
    ]
    return "\n".join(out + _footer(plan_path))

"""The rules behind the plots a user keeps: contacts against targets (missed
mine-like targets, false alarms: one rule shared with the report), and colours
that do not change between runs."""

from __future__ import annotations

from types import SimpleNamespace as NS

from tools.report.association import associate
from tools.report.plots import KNOWN_STATES, STATE_PALETTE, state_colour, vehicle_colour


def test_missed_targets_and_false_alarms():
    targets = [
        NS(north_m=0.0, east_m=0.0, kind=0),
        NS(north_m=50.0, east_m=0.0, kind=0),
        NS(north_m=0.0, east_m=50.0, kind=1),
    ]
    contacts = [
        ("AUV1", NS(north_m=1.0, east_m=1.0)),
        ("AUV2", NS(north_m=0.0, east_m=48.0)),
        ("AUV2", NS(north_m=100.0, east_m=100.0)),
        ("AUV1", NS(north_m=3.0, east_m=-3.0)),
    ]
    a = associate(targets, contacts, radius=5.0)
    assert list(a.hit) == [True, False, True] and list(a.missed) == [False, True, False]
    assert list(a.nearest) == [0, 2, -1, 0] and list(a.false_alarm) == [False, False, True, False]
    empty = associate([], contacts, radius=5.0)
    assert list(empty.false_alarm) == [True] * 4 and len(empty.missed) == 0


def test_colours_do_not_depend_on_what_else_a_run_holds():
    assert state_colour("line3") == state_colour("line3") and state_colour("line3") != state_colour("surface")
    assert state_colour("my_state") == state_colour("my_state")  # a name not known: its hash's
    run_a = NS(vehicles=["AUV1", "AUV2", "AUV3"])
    run_b = NS(vehicles=["AUV3", "AUV1", "AUV2"])
    assert [vehicle_colour(run_a, v) for v in ("AUV1", "AUV2", "AUV3")] == [
        vehicle_colour(run_b, v) for v in ("AUV1", "AUV2", "AUV3")
    ]
    assert len({vehicle_colour(run_a, v) for v in run_a.vehicles}) == 3


def test_state_colours_are_distinct_and_never_the_aborts_red():
    """The demo's log: reacquire was drawn in the red kept for aborts, and depth,
    linger and route in one blue. Every state of the shipped plans has a colour
    of its own; none is red."""
    import matplotlib.colors as mc

    assert len(set(KNOWN_STATES.values())) == len(KNOWN_STATES)  # each known name its own
    for c in STATE_PALETTE:
        h, sat, _v = mc.rgb_to_hsv(c[:3])
        assert not ((h < 15 / 360 or h > 345 / 360) and sat > 0.5), c  # no red in the palette
    demo = ["depth", "dive", "emergency", "gps_fix", "linger", "mission", "reacquire", "recover", "route", "survey"]
    assert len({state_colour(n) for n in demo}) == len(demo)
    assert len({state_colour(n) for n in ("depth", "linger", "route")}) == 3
    assert mc.to_hex(state_colour("reacquire")) != mc.to_hex("tab:red")


def test_every_state_of_the_shipped_plans_has_its_own_colour():
    import re

    from conftest import ROOT

    names = set()
    for plan in (ROOT / "missions").rglob("*.chasm"):
        names |= set(re.findall(r"^\s*state\s+([A-Za-z_][A-Za-z0-9_]*)", plan.read_text(), re.M))
    assert names and names <= set(KNOWN_STATES), sorted(names - set(KNOWN_STATES))

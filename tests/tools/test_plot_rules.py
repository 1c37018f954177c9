"""The rules behind the plots a user keeps: contacts against targets (missed
mine-like targets, false alarms: one rule shared with the report), and colours
that do not change between runs."""

from __future__ import annotations

from types import SimpleNamespace as NS

from tools.report.association import associate
from tools.report.plots import state_colour, vehicle_colour


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
    run_a = NS(vehicles=["AUV1", "AUV2", "AUV3"])
    run_b = NS(vehicles=["AUV3", "AUV1", "AUV2"])
    assert [vehicle_colour(run_a, v) for v in ("AUV1", "AUV2", "AUV3")] == [
        vehicle_colour(run_b, v) for v in ("AUV1", "AUV2", "AUV3")
    ]
    assert len({vehicle_colour(run_a, v) for v in run_a.vehicles}) == 3

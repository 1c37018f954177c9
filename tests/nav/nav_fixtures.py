"""Fixtures of the navigation tests: simulated surveys recorded once per
session (the real simulator in stepped mode, the real lcm-logger, auv-nav
running live beside them) and replayed by many tests. Test modules import
the fixtures; a cache keeps each recording to one per test session even
though every importing module registers its own copy of the fixture."""

from __future__ import annotations

import pytest
from conftest import BUILD, _ports, child_environment
from nav_common import record_survey

_recorded: dict = {}


def _once(name: str, make):
    if name not in _recorded:
        _recorded[name] = make()
    return _recorded[name]


@pytest.fixture(scope="session")
def survey(tmp_path_factory):
    """Two 300 m lines at 12 m after a minute on the surface (GPS), LBL on,
    DVL bottom lock; the sanitized auv-nav publishes AUV1.NAV_EKF live."""
    live = BUILD / "san" / "bin" / "auv-nav"
    if not live.exists():
        pytest.fail(f"{live} is not built: run `make build sanitize` first")
    return _once(
        "survey",
        lambda: record_survey(
            tmp_path_factory.mktemp("survey"),
            f"udpm://239.255.76.67:{next(_ports)}?ttl=0",
            child_environment(),
            ["--lines", "2", "--length", "300", "--spacing", "40"],
            live_nav=live,
        ),
    )


@pytest.fixture(scope="session")
def water_track_survey(tmp_path_factory):
    """One 250 m line with the DVL limited to 5 m altitude: water track only."""
    return _once(
        "water_track",
        lambda: record_survey(
            tmp_path_factory.mktemp("water_track"),
            f"udpm://239.255.76.67:{next(_ports)}?ttl=0",
            child_environment(),
            ["--lines", "1", "--length", "250", "--set", "sensors.dvl.max_altitude_m=5"],
        ),
    )

"""Every navigator plan in missions/ loads: `chasm check` with the built
plugins, and the abort scenarios override only what they say."""

from __future__ import annotations

import subprocess

import pytest
from conftest import BUILD, ROOT, c_program

PLANS = sorted((ROOT / "missions" / "examples").rglob("*.chasm"))


def check(*args) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(c_program("bin/chasm")), "check", "-P", str(BUILD / "plugins"), *map(str, args)],
        capture_output=True,
        text=True,
        timeout=60,
    )


def test_there_is_a_plan_per_safety_rule():
    names = {p.stem for p in PLANS}
    assert {
        "box_survey",
        "yoyo_transect",
        "max_depth",
        "min_altitude",
        "mission_timeout",
        "stale_nav",
        "operating_area",
        "leak",
    } <= names


@pytest.mark.parametrize("plan", PLANS, ids=[str(p.relative_to(ROOT / "missions")) for p in PLANS])
def test_example_plan_checks(plan):
    run = check(plan)
    assert run.returncode == 0 and ": ok (" in run.stdout, run.stdout + run.stderr


def test_every_example_carries_the_safety_rules():
    for plan in PLANS:
        text = plan.read_text()
        assert 'include "../common/safety.chasm"' in text or 'include "../yoyo_transect.chasm"' in text, plan


def test_a_bad_override_is_refused_with_its_position(tmp_path):
    bad = tmp_path / "bad.chasm"
    bad.write_text(f'param max_depth = 7 s\ninclude "{ROOT / "missions" / "examples" / "yoyo_transect.chasm"}"\n')
    run = check(bad)
    assert run.returncode == 1
    assert "safety_rules.chasm:17:37: " in run.stderr and "'s' is a duration" in run.stderr, run.stderr

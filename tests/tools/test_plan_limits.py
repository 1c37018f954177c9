"""The planner and the plugins agree on every limit (issue 14): the operating
area's vertex and character limits are read from the checks plugin's own
description (`chasm describe checks`), every operating area the planner
writes is bounded by them and still contains what it must, and every plan is
checked with `chasm check` before a scenario is written. `demo.py --polygon
... --vehicles N --plan-only` plans and checks for N from 1 to 16."""

from __future__ import annotations

import math
import random
import re
import subprocess
import sys

import pytest
from conftest import BUILD, c_program

from tools.plan.plugin_limits import LimitsError, check_plan, polygon_limits
from tools.plan.survey_geometry import area, buffer_convex, convex_hull, parse_polygon, simplify_convex_outer

DEMO = [sys.executable, "-m", "tools.demo"]
# The demo's target-field box, and a larger, irregular area with many vertices.
BOX = "0,0; 300,0; 300,240; 0,240"
CIRCLE = "; ".join(
    f"{300 + 250 * math.cos(2 * math.pi * k / 90):.1f},{300 + 250 * math.sin(2 * math.pi * k / 90):.1f}"
    for k in range(90)
)


def _inside_convex(p, poly, tol=1e-6) -> bool:
    s = 1 if sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(poly, poly[1:] + poly[:1])) > 0 else -1
    return all(
        s * ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) >= -tol
        for a, b in zip(poly, poly[1:] + poly[:1])
    )


def test_limits_are_read_from_the_plugin_description():
    lim = polygon_limits(BUILD)
    c_program("plugins/chasm_checks.so")
    text = subprocess.run(
        [str(BUILD / "bin/chasm"), "describe", "-P", str(BUILD / "plugins"), "checks"], capture_output=True, text=True
    ).stdout
    assert f"at most {lim.max_vertices} vertices and {lim.max_chars} characters" in text
    assert lim.max_vertices >= 3 and lim.max_chars > 100


def test_a_missing_build_is_a_clear_error(tmp_path):
    with pytest.raises(LimitsError, match="make build"):
        polygon_limits(tmp_path)


@pytest.mark.parametrize("seed", range(6))
def test_bounded_area_contains_the_original_and_keeps_within_the_limit(seed):
    rnd = random.Random(seed)
    pts = [(rnd.uniform(-2000, 2000), rnd.uniform(-1500, 1500)) for _ in range(400)]
    grown = buffer_convex(convex_hull(pts), rnd.uniform(20, 200))
    for limit in (4, 8, 16, 64):
        b = simplify_convex_outer(grown, limit)
        assert 3 <= len(b) <= limit
        assert all(_inside_convex(p, b) for p in grown)  # it grows, never cuts into a margin
        assert area(b) >= area(grown) * (1 - 1e-9)
        parse_polygon("; ".join(f"{n},{e}" for n, e in b))  # a valid simple polygon
    assert len(simplify_convex_outer(grown, len(grown))) == len(grown)  # nothing to do: unchanged


@pytest.mark.parametrize(
    "polygon, vehicles", [(BOX, 1), (BOX, 2), (BOX, 5), (BOX, 8), (CIRCLE, 8), (BOX, 11), (CIRCLE, 16), (BOX, 16)]
)
def test_demo_plans_and_checks_for_any_number_of_vehicles(tmp_path, polygon, vehicles, child_env):
    run = subprocess.run(
        DEMO
        + [
            "--polygon",
            polygon,
            "--vehicles",
            str(vehicles),
            "--plan-only",
            "--out",
            str(tmp_path),
            "--build",
            str(BUILD),
        ],
        capture_output=True,
        text=True,
        timeout=300,
        env=child_env,
    )
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    lim = polygon_limits(BUILD)
    plans = sorted((tmp_path / "plan").glob("AUV*.chasm"))
    assert len(plans) == vehicles and (tmp_path / "plan" / "mcm_demo.yaml").is_file()
    for plan in plans:
        text = plan.read_text()
        area_text = re.search(r'^param area\s*=\s*"([^"]*)"', text, re.M).group(1)
        assert len(parse_polygon(area_text)) <= lim.max_vertices and len(area_text) <= lim.max_chars
        legs = [tuple(map(float, m)) for m in re.findall(r"to_north = ([-\d.]+) m, to_east = ([-\d.]+) m", text)]
        poly = parse_polygon(area_text)
        assert legs and all(_inside_convex(p, poly) for p in legs)  # every leg inside the operating area
    assert check_plan(plans[-1], BUILD) == []  # and `chasm check` agrees, independently


def test_a_plan_the_plugins_refuse_is_never_written_into_a_scenario(tmp_path):
    """A limit the planner does not know of (a speed beyond the guidance
    plugin's range) is caught by `chasm check`: exit 2, the loader's message,
    no scenario."""
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "tools.plan.plan_survey",
            "--polygon",
            BOX,
            "--vehicles",
            "2",
            "--range",
            "40",
            "--speed-mps",
            "1000",
            "--out",
            str(tmp_path),
            "--build",
            str(BUILD),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 2, run.stdout + run.stderr
    assert "does not load" in run.stderr and "no scenario written" in run.stderr
    assert "Traceback" not in run.stderr
    assert not list(tmp_path.glob("*.yaml"))

"""`chasm check` beyond loading (issue 35, item 4): each kind of finding shown
by a plan of tests/chasm/findings/ at its file:line:col, a finding a plan marks
expected counted instead of shown, and the shipped plans clean or marked."""

from __future__ import annotations

import re

from chasm_common import run
from conftest import ROOT

FINDINGS = ROOT / "tests" / "chasm" / "findings"
LINE = re.compile(r"^(?P<file>[^:]+):(?P<line>\d+):(?P<col>\d+): warning: \[(?P<kind>[a-z-]+)\] (?P<text>.*)$")


def findings(stdout: str) -> list[tuple[str, int, int, str]]:
    return [
        (m["file"].rsplit("/", 1)[-1], int(m["line"]), int(m["col"]), m["kind"])
        for m in map(LINE.match, stdout.splitlines())
        if m
    ]


def test_each_kind_of_finding_at_its_position(variant_dir, child_env):
    plans = sorted(FINDINGS.glob("*.chasm"))
    p = run([variant_dir / "bin" / "chasm", "check", *plans], child_env)
    assert p.returncode == 0, p.stderr  # findings warn: the plans load and run
    assert sorted(findings(p.stdout)) == [
        ("never_fires.chasm", 11, 5, "never-fires"),  # deep and shallow: > 10 m and < 5 m
        ("never_fires.chasm", 14, 9, "never-fires"),  # when false
        ("never_fires.chasm", 20, 5, "never-fires"),  # behind `when true` of its own state
        ("no_way_out.chasm", 11, 7, "no-way-out"),
        ("shadowed_abort.chasm", 7, 1, "shadowed-abort"),
        ("unreachable.chasm", 14, 7, "unreachable"),
        ("unwritten_output.chasm", 5, 8, "unwritten-output"),
    ], p.stdout
    assert "ask nav.depth_m for values that do not meet" in p.stdout
    assert "expected.chasm: ok" in p.stdout and "(1 finding marked expected in the plan)" in p.stdout
    assert "never_fires.chasm: 3 findings" in p.stdout


def test_the_shipped_plans_are_clean_or_say_why(variant_dir, child_env):
    plans = sorted(p for p in (ROOT / "missions").rglob("*.chasm") if "common" not in p.parts)
    p = run([variant_dir / "bin" / "chasm", "check", *plans], child_env)
    assert p.returncode == 0, p.stderr
    assert p.stdout.count(": ok (") == len(plans)
    assert findings(p.stdout) == [], p.stdout

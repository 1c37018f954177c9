"""`-D name=value` is a value, never plan text (issue 12 item 7): every
injection attempt is refused with a `<-D name>` error and exit 2, an unknown
name gets a did-you-mean, a value of the wrong kind or unit is refused, and a
good override still wins over the plan's value. The same rule holds for the
manager's -D."""

from __future__ import annotations

import pytest
from chasm_common import run

PLAN = """\
param depth = 10 m
param label = "survey"
param fast = false
input nav.depth : double m
output setpoint.depth : double m
state dive {
  do set setpoint.depth = $depth on entry
  test deep : nav.depth > $depth
  when deep -> hold
}
state hold {
}
"""

# (value given to -D depth=..., what the error must say)
INJECTIONS = [
    ("12 m\nstate evil {\n}", "control character"),
    ("12 m\r\nstate evil { }", "control character"),
    ("12 m # comment", "takes one value"),
    ("12 m }", "takes one value"),
    ("12 m } state evil {", "takes one value"),
    ("12 m {", "takes one value"),
    ('12 m "x"', "takes one value"),
    ("12 m 13 m", "takes one value"),
    ("$label", "must be a constant"),
    ("nav.depth", "the value is a name ('nav.depth'), but the plan's 'depth' is a length"),
    ('"12 m"', "the value is a string"),
    ("12 s", "the value is a duration"),
    ("12", "the value is a plain number"),
    ("true", "the value is true or false"),
    ("", "has no value"),
    ("   ", "has no value"),
    ("12 furlongs", "unknown unit"),
    ("12 m\x7f", "control character"),
]


@pytest.fixture
def chasm(variant_dir, child_env, tmp_path):
    exe = variant_dir / "bin" / "chasm"
    plan = tmp_path / "plan.chasm"
    plan.write_text(PLAN)

    def call(*defines):
        args = []
        for d in defines:
            args += ["-D", d]
        return run([exe, "check", *args, plan], child_env)

    return call


@pytest.mark.parametrize("value,error", INJECTIONS, ids=[repr(v)[:24] for v, _ in INJECTIONS])
def test_injection_attempts_are_refused(chasm, value, error):
    p = chasm(f"depth={value}")
    assert p.returncode == 2, p.stdout + p.stderr
    assert "<-D depth>:1:" in p.stderr and error in p.stderr, p.stderr
    assert "evil" not in p.stdout and ": ok (" not in p.stdout
    assert "Traceback" not in p.stderr


def test_an_unknown_name_is_refused_with_a_hint(chasm):
    p = chasm("depht=12 m")
    assert p.returncode == 2
    assert "<-D depht>:1:1: error: -D depht: the plan has no parameter 'depht' (did you mean 'depth'?)" in p.stderr
    p = chasm("nothing_like_it=1")
    assert p.returncode == 2 and "the plan has no parameter 'nothing_like_it'" in p.stderr


@pytest.mark.parametrize("define", ["=12 m", "de pth=12 m", "depth\n=12 m", "1depth=3 m", "depth"])
def test_a_bad_name_is_a_usage_error(chasm, define):
    p = chasm(define)
    assert p.returncode == 2, p.stderr
    assert "-D" in p.stderr


@pytest.mark.parametrize(
    "define",
    ["depth=12 m", "depth=12.5m", "depth=-3 ft", "depth=1.0e1 m", 'label="a # b }"', "fast=true", 'label="line"'],
)
def test_good_overrides_load(chasm, define):
    p = chasm(define)
    assert p.returncode == 0, p.stderr
    assert ": ok (2 states" in p.stdout


def test_the_override_wins(variant_dir, child_env, tmp_path):
    plan = tmp_path / "plan.chasm"
    plan.write_text(PLAN)
    inputs = tmp_path / "in.txt"
    inputs.write_text("0.5 nav.depth = 11 m\n")
    exe = variant_dir / "bin" / "chasm"
    p = run([exe, "run", "-D", "depth=12 m", plan, "--inputs", inputs, "--until", "1"], child_env)
    assert p.returncode == 0, p.stderr
    assert "hold" not in p.stdout  # 11 m is not deeper than the overridden 12 m
    p = run([exe, "run", plan, "--inputs", inputs, "--until", "1"], child_env)
    assert "hold" in p.stdout  # but deeper than the plan's 10 m

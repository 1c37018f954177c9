"""The `chasm` tool: check, dot and run (scripted inputs, CSV, hot plug,
parameters, includes, plugin path by flag and environment)."""

from __future__ import annotations

import re
import shutil

import pytest
from chasm_common import BAD_PLANS, PLANS, run


@pytest.fixture
def chasm(variant_dir, child_env, tmp_path):
    child_env["TMPDIR"] = str(tmp_path)
    child_env.pop("CHASM_PLUGIN_PATH", None)
    exe = variant_dir / "bin" / "chasm"

    def call(*args, env=None, **kw):
        return run([exe, *args], env or child_env, **kw)

    call.plugins = variant_dir / "plugins"
    call.exe = exe
    call.env = child_env
    return call


def transitions(stdout: str) -> list[tuple[float, str]]:
    """(time, state) of every printed line of `chasm run`."""
    out = []
    for line in stdout.splitlines():
        m = re.match(r"\s*([\d.]+) s  (\S+)\s+<- ", line)
        if m:
            out.append((float(m.group(1)), m.group(2)))
    return out


def test_check_good_plans(chasm):
    p = chasm("check", "-P", chasm.plugins, PLANS / "survey.chasm", PLANS / "auv1.chasm", PLANS / "plugin_demo.chasm")
    assert p.returncode == 0, p.stderr
    assert p.stdout.count(": ok (") == 3
    assert "survey.chasm: ok (9 states, 5 tests, 6 variables)" in p.stdout


def test_check_reports_every_plan_and_fails(chasm):
    p = chasm(
        "check", PLANS / "survey.chasm", BAD_PLANS / "43_many_errors.chasm", BAD_PLANS / "01_statement_typo.chasm"
    )
    assert p.returncode == 1
    assert "survey.chasm: ok" in p.stdout
    assert len([l for l in p.stderr.splitlines() if ": error: " in l]) == 4
    assert "43_many_errors.chasm: 3 errors" in p.stderr


def test_default_plugin_path_is_the_builds(chasm, tmp_path):
    """No -P and no $CHASM_PLUGIN_PATH: the plugins built beside the program."""
    p = chasm("check", PLANS / "plugin_demo.chasm")
    assert p.returncode == 0, p.stderr
    # a copy of the program with no plugins beside it has an empty path, and
    # the follow-on errors say the plugin did not load, not "uses no plugins"
    lone = tmp_path / "bin" / "chasm"
    lone.parent.mkdir()
    shutil.copy2(chasm.exe, lone)
    p = run([lone, "check", PLANS / "plugin_demo.chasm"], chasm.env)
    assert p.returncode == 1 and "the plugin path is empty" in p.stderr
    assert "uses no plugins" not in p.stderr
    assert "unknown behavior 'hold' (no plugin named by `use` loaded" in p.stderr


def test_plugin_path_from_environment(chasm, tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    env = dict(chasm.env, CHASM_PLUGIN_PATH=str(empty))
    p = chasm("check", PLANS / "plugin_demo.chasm", env=env)
    assert p.returncode == 1 and "plugin 'test_basic' not found" in p.stderr
    env = dict(chasm.env, CHASM_PLUGIN_PATH=f"/nonexistent:{chasm.plugins}")
    p = chasm("check", PLANS / "plugin_demo.chasm", env=env)
    assert p.returncode == 0, p.stderr


def test_dot(chasm):
    p = chasm("dot", PLANS / "survey.chasm")
    assert p.returncode == 0, p.stderr
    out = p.stdout
    assert out.startswith("digraph chasm {") and out.rstrip().endswith("}")
    assert "subgraph cluster_0 {" in out and 'label="mission"' in out
    assert '[label="descend"]' in out
    assert 'label="resume deep: got_fix"' in out
    assert 'label="leak or nav_stale"' in out
    assert out.count("->") >= 12


def test_run_scripted_inputs(chasm):
    p = chasm(
        "run",
        PLANS / "survey.chasm",
        "--inputs",
        PLANS / "survey.inputs",
        "--until",
        "120",
        "--watch",
        "setpoint.speed_mps",
    )
    assert p.returncode == 0, p.stderr
    assert transitions(p.stdout) == [(0.0, "mission/descend"), (22.0, "mission/survey/leg1")]
    assert "setpoint.speed_mps=1.5" in p.stdout.splitlines()[1]
    assert "<- at_depth [at_depth=true]" in p.stdout


def test_run_csv_and_expect(chasm):
    args = ["run", PLANS / "survey.chasm", "--inputs", PLANS / "survey.csv", "--until", "40"]
    p = chasm(*args, "--expect", "emergency")
    assert p.returncode == 0, p.stdout + p.stderr
    # the depth stops updating after 30 s: the stale-navigation abort fires at 35.1 s
    assert transitions(p.stdout)[-1] == (35.1, "emergency")
    p = chasm(*args, "--expect", "mission/survey/leg2")
    assert p.returncode == 4 and "expected to end in 'mission/survey/leg2'" in p.stderr


def test_run_vehicle_parameters(chasm, tmp_path):
    """auv1.chasm sets depth = 15 m over the template's 10 m; -D wins over both.
    Tests first run in the first step (0.1 s), so `for 10 s` holds at 10.1 s."""
    inputs = tmp_path / "in.txt"
    inputs.write_text("".join(f"{t} s nav.depth_m = 15 m\n" for t in range(0, 60, 2)))
    p = chasm("run", PLANS / "auv1.chasm", "--inputs", inputs, "--until", "30")
    assert transitions(p.stdout)[1] == (10.1, "mission/survey/leg1"), p.stdout
    p = chasm("run", PLANS / "survey.chasm", "--inputs", inputs, "--until", "30")
    assert len(transitions(p.stdout)) == 1  # 15 m is not within 0.5 m of 10 m
    p = chasm("run", "-D", "depth=1500 cm", PLANS / "survey.chasm", "--inputs", inputs, "--until", "30")
    assert transitions(p.stdout)[1] == (10.1, "mission/survey/leg1"), p.stdout + p.stderr


def test_run_hot_plug(chasm, tmp_path):
    broken = tmp_path / "chasm_test_basic.so"
    broken.write_bytes(b"\x7fELF garbage")
    p = chasm(
        "run",
        "-P",
        chasm.plugins,
        PLANS / "plugin_demo.chasm",
        "--inputs",
        PLANS / "plugin_demo.inputs",
        "--watch",
        "test.out",
        "-v",
        "--hotplug",
        f"1:{chasm.plugins / 'chasm_test_basic_v2.so'}",
        "--hotplug",
        f"1.5:{broken}",
    )
    assert p.returncode == 0, p.stderr
    out = p.stdout
    assert "hot plug of" in out and "done" in out
    assert f"hot plug of '{broken}' failed: cannot load plugin file" in out
    assert "plugin 'test_basic' version 1 (1.0.0) unloaded" in out
    # version 1 keeps running until `work` is left at 2 s; version 2 after re-entry at 3 s
    lines = {s: l for l in out.splitlines() for (t, s) in transitions(l)}
    assert "test.out=3" in lines["pause"]
    assert "test.out=6" in lines["finish"]
    assert out.rstrip().endswith("end: done after 53 cycles, in finish")


def test_run_inputs_errors(chasm, tmp_path):
    bad = tmp_path / "bad.txt"
    bad.write_text("0 s nav.depth_m = 5 m\n1 s nav.dpth = 3 m\n2 s nav.depth_m = 4 s\n")
    p = chasm("run", PLANS / "survey.chasm", "--inputs", bad)
    assert p.returncode == 1
    assert f"{bad}:2:5: error: the plan has no variable 'nav.dpth'" in p.stderr


def test_usage(chasm):
    p = chasm("frobnicate")
    assert p.returncode == 2 and "usage:" in p.stderr


def test_describe_plugin(chasm):
    p = chasm("describe", "-P", chasm.plugins, "test_basic")
    assert p.returncode == 0, p.stderr
    assert p.stdout.splitlines()[0].startswith("plugin test_basic 1.0.0 (")
    assert "  behavior hold: hold a value" in p.stdout
    assert "value          double m      required, range [-100, 100]  # depth to hold" in p.stdout
    assert "  test handler above: x > limit" in p.stdout
    p = chasm("describe", "-P", chasm.plugins, "guidance")  # a real plugin: parameters of two forms
    assert p.returncode == 0, p.stderr
    assert "optional, no default, range [-1e+06, 1e+06]  # box corner, north (box form)" in p.stdout, p.stdout
    assert "e+15" not in p.stdout
    p = chasm("describe", "-P", chasm.plugins, "team")  # optional without a default, and no range
    assert p.returncode == 0, p.stderr
    assert "altitude       double m      optional, no default  # altitude instead of a depth" in p.stdout, p.stdout
    assert "e+15" not in p.stdout
    p = chasm("describe", "-P", chasm.plugins, "test_nosym")
    assert p.returncode == 1 and "does not export 'chasm_plugin'" in p.stderr

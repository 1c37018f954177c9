"""Hostile plugin files through every loader of the `chasm` tool: `chasm check
-P DIR`, $CHASM_PLUGIN_PATH, `chasm run --hotplug` and `chasm describe`.
Each file is refused with a clear reason at the plan's `use`, no run dies by a
signal or gives a sanitizer report, a running mission goes on untouched, and
no private copy is left in $TMPDIR. Both builds (variant_dir)."""

from __future__ import annotations

import re
import subprocess

import pytest
from chasm_common import PLANS, run
from plugin_corpus import BUILT, HANG, SPECIAL, Case, built_cases, byte_cases, make_special


def _corpus(plugins) -> list[Case]:
    good = (plugins / "chasm_test_basic.so").read_bytes()
    return byte_cases(good) + built_cases(plugins)


def _no_signal(p: subprocess.CompletedProcess) -> None:
    assert p.returncode >= 0, f"killed by signal {-p.returncode}:\n{p.stderr}"
    assert "Sanitizer" not in p.stderr, p.stderr


@pytest.fixture
def env(child_env, tmp_path):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    child_env["TMPDIR"] = str(tmp)
    child_env.pop("CHASM_PLUGIN_PATH", None)
    yield child_env
    assert list(tmp.iterdir()) == [], "private plugin copies were left behind"


def test_the_corpus_is_big_enough(variant_dir):
    cases = _corpus(variant_dir / "plugins")
    assert len(cases) + len(SPECIAL) + 1 >= 45
    assert len({c.name for c in cases}) == len(cases)


def test_check_refuses_every_hostile_file_at_its_use(variant_dir, env, tmp_path):
    """One `chasm check` of one plan per hostile file: plan i uses plugin c<i>,
    found in -P DIR as chasm_c<i>.so. Every plan fails at 1:5 with the reason."""
    plugins = variant_dir / "plugins"
    pdir, plans = tmp_path / "p", tmp_path / "plans"
    pdir.mkdir()
    plans.mkdir()
    expect: dict[str, str] = {}
    cases = _corpus(plugins)
    for i, c in enumerate(cases):
        (pdir / f"chasm_c{i}.so").write_bytes(c.data)
        expect[f"c{i}"] = c.reason
    for kind in SPECIAL:
        expect[kind] = make_special(kind, pdir / f"chasm_{kind}.so")
    expect["hang"] = HANG[1]
    (pdir / "chasm_hang.so").write_bytes((plugins / f"chasm_{HANG[0]}.so").read_bytes())
    files = []
    for name in expect:
        f = plans / f"{name}.chasm"
        f.write_text(f"use {name}\nstate a {{\n}}\n")
        files.append(f.name)
    p = run([variant_dir / "bin" / "chasm", "check", "-P", pdir, *files], env, cwd=plans, timeout=300)
    _no_signal(p)
    assert p.returncode == 1 and p.stdout == "", p.stdout
    for name, reason in expect.items():
        lines = [l for l in p.stderr.splitlines() if l.startswith(f"{name}.chasm:")]
        assert len(lines) == 1, (name, p.stderr)
        assert lines[0].startswith(f"{name}.chasm:1:5: error: plugin '{name}': "), lines[0]
        assert lines[0].count(f"plugin '{name}'") == 1, lines[0]  # named once
        assert reason in lines[0], (name, reason, lines[0])


def test_plugin_path_from_environment_refuses_too(variant_dir, env, tmp_path):
    pdir = tmp_path / "p"
    pdir.mkdir()
    good = (variant_dir / "plugins" / "chasm_test_basic.so").read_bytes()
    (pdir / "chasm_test_basic.so").write_bytes(good[: len(good) // 2])
    env["CHASM_PLUGIN_PATH"] = f"{tmp_path / 'empty'}:{pdir}"
    p = run([variant_dir / "bin" / "chasm", "check", PLANS / "plugin_demo.chasm"], env)
    _no_signal(p)
    assert p.returncode == 1
    assert re.search(
        r"plugin_demo.chasm:2:5: error: plugin 'test_basic': cannot load plugin file '.*': .*truncated", p.stderr
    ), p.stderr


def test_a_bad_file_not_used_by_the_plan_is_never_opened(variant_dir, env, tmp_path):
    pdir = tmp_path / "p"
    pdir.mkdir()
    (pdir / "chasm_unused.so").write_bytes(b"\x7fELF truncated")
    make_special("fifo", pdir / "chasm_fifo.so")
    p = run(
        [
            variant_dir / "bin" / "chasm",
            "check",
            "-P",
            pdir,
            "-P",
            variant_dir / "plugins",
            PLANS / "plugin_demo.chasm",
        ],
        env,
    )
    assert p.returncode == 0, p.stderr


def test_hot_plug_of_every_hostile_file_leaves_the_mission_running(variant_dir, env, tmp_path):
    plugins = variant_dir / "plugins"
    args = [
        "run",
        "-P",
        plugins,
        PLANS / "plugin_demo.chasm",
        "--inputs",
        PLANS / "plugin_demo.inputs",
        "--watch",
        "test.out",
    ]
    exe = variant_dir / "bin" / "chasm"
    base = run([exe, *args], env)
    assert base.returncode == 0, base.stderr
    hp: list[str] = []
    expect: dict[str, str] = {}
    for i, c in enumerate(_corpus(plugins)):
        f = tmp_path / f"c{i}" / "chasm_test_basic.so"
        f.parent.mkdir()
        f.write_bytes(c.data)
        expect[str(f)] = c.reason
    for kind in SPECIAL:
        f = tmp_path / kind / "chasm_test_basic.so"
        f.parent.mkdir()
        expect[str(f)] = make_special(kind, f)
    for k, f in enumerate(expect):
        hp += ["--hotplug", f"{0.5 + 0.1 * (k % 30)}:{f}"]
    p = run([exe, *args, *hp], env, timeout=300)
    _no_signal(p)
    assert p.returncode == 0, p.stderr
    for f, reason in expect.items():
        line = next((l for l in p.stdout.splitlines() if f"hot plug of '{f}'" in l), "")
        assert "failed: " in line and reason in line, (f, reason, line)
    # the mission is the same as without any hot plug
    strip = [l for l in p.stdout.splitlines() if "hot plug of" not in l]
    assert strip == base.stdout.splitlines()


@pytest.mark.parametrize("name,reason", [*BUILT, ("truncated", "truncated"), ("directory", "directory")])
def test_describe_refuses_with_a_reason(variant_dir, env, tmp_path, name, reason):
    plugins = variant_dir / "plugins"
    if name == "truncated":
        good = (plugins / "chasm_test_basic.so").read_bytes()
        f = tmp_path / "chasm_cut.so"
        f.write_bytes(good[:3000])
    elif name == "directory":
        f = tmp_path / "chasm_dir.so"
        make_special("directory", f)
    else:
        f = plugins / f"chasm_{name}.so"
    p = run([variant_dir / "bin" / "chasm", "describe", f], env)
    _no_signal(p)
    assert p.returncode == 1
    assert reason.replace("does not export", "does not export 'chasm_plugin'") in p.stderr, p.stderr


def test_describe_refuses_a_name_that_is_not_a_plugin_name(variant_dir, env):
    p = run([variant_dir / "bin" / "chasm", "describe", "-P", variant_dir / "plugins", "Test.basic"], env)
    assert p.returncode == 1
    assert "'Test.basic' is not a plugin name" in p.stderr


def test_a_plugin_limit_is_a_load_error_and_values_within_it_load(variant_dir, env, tmp_path):
    """CHASM_PLUGIN_CHECK (chasm_plugin.h): the plugin's own limit of a value
    is checked at load, at the value's file:line:col; within it the plan loads
    and runs. (The refusals are in bad_plans/56_plugin_limit.chasm.)"""
    plan = tmp_path / "ok.chasm"
    plan.write_text('use test_limits\nvar test.count : int\nstate a {\n    do route(points = "1; 2; 3; 4")\n}\n')
    exe = variant_dir / "bin" / "chasm"
    p = run([exe, "check", "-P", variant_dir / "plugins", plan], env)
    assert p.returncode == 0, p.stderr
    plan.write_text(plan.read_text().replace('"1; 2; 3; 4"', '""'))
    p = run([exe, "check", "-P", variant_dir / "plugins", plan], env)
    assert p.returncode == 1
    assert f"{plan}:4:23: error: parameter 'points' of 'route': 0 points, this plugin takes 1 to 4" in p.stderr, (
        p.stderr
    )

"""Every limit of the plan loader is either gone or a load error that names
it (issue 12 item 5; the table is in docs/chasm.md, "Limits"): one case at
each limit and one past it, in both builds."""

from __future__ import annotations

import pytest
from chasm_common import run

STRING_MAX = 1023
STATE_DEPTH = 32
INCLUDE_DEPTH = 16


@pytest.fixture
def check(variant_dir, child_env, tmp_path):
    exe = variant_dir / "bin" / "chasm"

    def call(text: str, name="plan.chasm", *extra):
        path = tmp_path / name
        path.write_text(text)
        return run([exe, "check", *extra, path], child_env)

    call.dir = tmp_path
    call.exe = exe
    call.env = child_env
    return call


def runs_to(variant_dir, env, tmp_path, plan: str, inputs: str) -> str:
    (tmp_path / "p.chasm").write_text(plan)
    (tmp_path / "in.txt").write_text(inputs)
    p = run(
        [variant_dir / "bin" / "chasm", "run", tmp_path / "p.chasm", "--inputs", tmp_path / "in.txt", "--until", "1"],
        env,
    )
    assert p.returncode == 0, p.stderr
    return p.stdout


@pytest.mark.parametrize("digits", [10, 62, 63, 64, 300, 5000])
def test_numbers_of_any_length_are_read_whole(variant_dir, child_env, tmp_path, digits):
    """`1.000...e3 m` is 1000 m however many zeros (the lexer cut at 63)."""
    number = "1." + "0" * digits + "e3"
    plan = f"input x : double m\ntest big : x > {number} m\nstate a {{\n when big -> b\n}}\nstate b {{\n}}\n"
    out = runs_to(variant_dir, child_env, tmp_path, plan, "0.2 x = 999 m\n0.5 x = 1001 m\n")
    lines = [l for l in out.splitlines() if " b " in f" {l} "]
    assert lines and lines[0].lstrip().startswith("0.5"), out


def string_plan(n: int) -> str:
    return f'input txt : string\ntest same : txt == "{"a" * n}"\nstate a {{\n when same -> b\n}}\nstate b {{\n}}\n'


def test_a_string_at_the_limit_loads_and_compares(variant_dir, child_env, tmp_path):
    out = runs_to(variant_dir, child_env, tmp_path, string_plan(STRING_MAX), f'0.3 txt = "{"a" * STRING_MAX}"\n')
    assert any(l.split()[2] == "b" for l in out.splitlines() if len(l.split()) > 2), out


def test_a_string_past_the_limit_is_a_load_error(check):
    p = check(string_plan(STRING_MAX + 1))
    assert p.returncode == 1
    assert "plan.chasm:2:" in p.stderr and "at most 1023 (CHASM_STRING_MAX)" in p.stderr


def nested(depth: int) -> str:
    text = "".join(f"{'  ' * i}state s{i} {{\n" for i in range(depth))
    return text + "".join(f"{'  ' * i}}}\n" for i in reversed(range(depth)))


def test_states_nest_to_the_limit(check):
    assert check(nested(STATE_DEPTH)).returncode == 0
    p = check(nested(STATE_DEPTH + 1))
    assert p.returncode == 1
    assert f"plan.chasm:{STATE_DEPTH + 1}:" in p.stderr
    assert "more than 32 levels, CHASM_MAX_STATE_DEPTH" in p.stderr


def test_includes_nest_to_the_limit(check):
    d = check.dir
    for depth in (INCLUDE_DEPTH, INCLUDE_DEPTH + 1):
        for i in range(depth):
            nxt = f'include "inc{i + 1}.chasm"\n' if i + 1 < depth else "state leaf {\n}\n"
            (d / f"inc{i}.chasm").write_text(nxt)
        p = run([check.exe, "check", d / "inc0.chasm"], check.env)
        if depth == INCLUDE_DEPTH:
            assert p.returncode == 0, p.stderr
        else:
            assert p.returncode == 1 and "CHASM_MAX_INCLUDE_DEPTH" in p.stderr, p.stderr


def test_long_names_and_paths_are_never_cut(check):
    """A state path longer than any buffer (512, 1024) still resolves exactly:
    two paths that agree in their first 2000 characters stay distinct."""
    long = "n" * 1500
    plan = (
        f"state {long} {{\n  state {long}_x {{\n  }}\n  state {long}_y {{\n  }}\n"
        f"  when elapsed > 1 s -> {long}/{long}_y\n}}\n"
    )
    p = check(plan)
    assert p.returncode == 0, p.stderr
    p = check(plan.replace(f"-> {long}/{long}_y", f"-> {long}/{long}_z"))
    assert p.returncode == 1 and ":6:25: error: unknown target state" in p.stderr, p.stderr


def test_a_long_line_is_fine(check):
    line = "# " + "x" * 200000 + "\n"
    assert check(line + "state a {\n}\n").returncode == 0


def test_too_many_errors_says_so(check):
    p = check("".join(f"bogus{i}\n" for i in range(800)))
    assert p.returncode == 1
    errors = [l for l in p.stderr.splitlines() if ": error: " in l]
    assert len(errors) == 500
    assert "too many errors: only the first 499 are shown" in errors[-1]


@pytest.mark.parametrize("what,n", [("-D", 65), ("-P", 65)])
def test_command_line_lists_past_their_limit_are_usage_errors(check, what, n):
    args = []
    for i in range(n):
        args += [what, f"p{i}=1" if what == "-D" else f"/nonexistent{i}"]
    p = check("state a {\n}\n", "plan.chasm", *args)
    assert p.returncode == 2 and "at most 64" in p.stderr, p.stderr


@pytest.mark.parametrize(
    "name,text,code,error",
    [
        ("i.txt", "1e300 x = 1 m\n", 1, "i.txt:1:1: error: an input's time must be between 0 s and 1e+09 s"),
        ("i.txt", "-1 x = 1 m\n", 1, "i.txt:1:1: error: an input's time must be between"),
        ("i.txt", "1 n = 1e300\n", 1, "i.txt:1:7: error: 'n' is an int: 1e+300 is out of its range"),
        ("i.csv", "time,n\n1,1e300\n", 1, "i.csv:2:1: error: 'n' is an int"),
        ("i.csv", "time,x\nnan,1\n", 1, "i.csv:2:1: error: an input's time must be between"),
        ("i.csv", "time," + ",".join(["x"] * 257) + "\n", 1, "i.csv:1:1: error: more than 256 columns"),
    ],
)
def test_chasm_run_inputs_at_the_extremes(variant_dir, child_env, tmp_path, name, text, code, error):
    """Times and integers out of range are file:line:col errors, never an
    overflowing conversion (UBSan in the sanitized build)."""
    (tmp_path / "p.chasm").write_text("input x : double m\ninput n : int\nstate a {\n}\n")
    (tmp_path / name).write_text(text)
    p = run([variant_dir / "bin" / "chasm", "run", tmp_path / "p.chasm", "--inputs", tmp_path / name], child_env)
    assert p.returncode == code and error in p.stderr, p.stderr


@pytest.mark.parametrize("flag", ["--dt", "--until"])
@pytest.mark.parametrize("value", ["1e300", "-5", "nan", "inf"])
def test_chasm_run_durations_out_of_range_are_usage_errors(variant_dir, child_env, tmp_path, flag, value):
    (tmp_path / "p.chasm").write_text("state a {\n}\n")
    (tmp_path / "i.txt").write_text("")
    p = run(
        [variant_dir / "bin" / "chasm", "run", tmp_path / "p.chasm", "--inputs", tmp_path / "i.txt", flag, value],
        child_env,
    )
    assert p.returncode == 2 and "is not a duration" in p.stderr, p.stderr

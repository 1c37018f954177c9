"""The binding-file parser on hostile files (issue 12 items 5 and 6): no
fixed-size buffer cuts or splits a line, every refusal is `file:line:col`,
and a short deterministic fuzz run (ASan+UBSan) of the parser; `make fuzz`
runs the long one."""

from __future__ import annotations

import subprocess

import pytest
from conftest import ROOT, c_program

from auvlcm import programs

HERE = ROOT / "tests" / "managers"
CORPUS = HERE / "bind_corpus"

GOOD = "input nav ${VEHICLE}.NAV nav_solution_t\noutput setpoint ${VEHICLE}.SETPOINT setpoint_t\n"

# (binding file text, exit code, message expected on stderr)
CASES = [
    (GOOD, None, None),
    ("# " + "c" * 5000 + "\n" + GOOD, None, None),  # a long comment line is not split
    (
        "input nav " + "${VEHICLE}" * 20 + ".NAV nav_solution_t\n" + GOOD.splitlines()[1] + "\n",
        1,
        "b.bind:1:11: channel name too long (LCM allows 63 characters)",
    ),
    ("input nav " + "C" * 64 + " nav_solution_t\n" + GOOD, 1, "b.bind:1:11: channel name too long"),
    ("input nav " + "C" * 63 + " nav_solution_t\n" + GOOD.splitlines()[1] + "\n", None, None),
    (GOOD + "input " + "p" * 3000 + " X.Y nav_solution_t\n", None, None),  # a long prefix binds nothing, but is fine
    (GOOD + "input gps X.GPS gps_fix_t optional extra\n", 1, "b.bind:3:1: expected `input|output"),
    (
        GOOD + "input gps X.GPS gps_fix_t optional a b c d\n",
        1,
        "b.bind:3:38: unexpected 'b' after the line's last field",
    ),
    (GOOD + "input gps X.GPS \x01gps_fix_t\n", 1, "b.bind:3:17: unexpected byte 0x01"),
    (GOOD + "input gps X.GPS gps_fix_t\xff\n", 1, "unexpected byte 0xc3"),
    (GOOD + "input gps X.GPS " + "t" * 500 + "\n", 1, "b.bind:3:17: unknown message type 'tttt"),
    (GOOD + "input nav X.NAV2 nav_solution_t\n", 1, "b.bind:3:7: prefix 'nav' is already bound on line 1"),
    (
        "input nav ${VEHICLE}.NAV nav_solution_t\x00\n" + GOOD.splitlines()[1] + "\n",
        1,
        "b.bind:1:40: unexpected NUL byte",
    ),
]


def load(bind, lcm_url, child_env, sanitized: bool, expect_running: bool) -> tuple[int | None, str]:
    """The manager on dive.chasm with `bind`: a good file loads and runs (it is then
    stopped, and must not have tripped a sanitizer); a bad one exits. Returns its
    exit status (None when it ran) and what it wrote to stderr."""
    cmd = programs.chasm_manager(
        c_program("bin/chasm-manager", sanitized).parents[1],
        plan=HERE / "dive.chasm",
        bind=bind,
        vehicle="AUV1",
        name="NAVIGATOR",
        lcm_url=lcm_url,
    )
    if not expect_running:
        run = subprocess.run(cmd, env=child_env, capture_output=True, text=True, timeout=30)
        return run.returncode, run.stderr
    p = subprocess.Popen(cmd, env=child_env, stderr=subprocess.PIPE, text=True)
    try:
        out = ""
        for line in p.stderr:
            out += line
            if "running" in line:
                break
    finally:
        p.terminate()
        p.wait(20)
    assert "NAVIGATOR: running" in out, out
    assert p.returncode not in (86, 87), out  # ASan, UBSan
    return None, out


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
@pytest.mark.parametrize("text,code,error", CASES, ids=[f"case{i}" for i in range(len(CASES))])
def test_hostile_binding_files(tmp_path, lcm_url, child_env, sanitized, text, code, error):
    bind = tmp_path / "b.bind"
    bind.write_bytes(text.encode("utf-8"))
    returncode, stderr = load(bind, lcm_url, child_env, sanitized, expect_running=code is None)
    if code is not None:
        assert returncode == code and error in stderr, stderr


def test_fuzz_binding_parser_short(build_dir, child_env, tmp_path):
    exe = build_dir / "san" / "bin" / "chasm_bind_fuzz"
    assert exe.exists(), f"{exe} is not built: run `make sanitize`"
    p = subprocess.run(
        [exe, "--runs", "30000", "--seed", "11", CORPUS],
        env=child_env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 0, p.stdout + p.stderr
    assert "no crash" in p.stdout
    assert not list(tmp_path.glob("chasm-crash-*"))


# `include "FILE"` (docs/managers.md, "Bindings"): {file: text} written under
# tmp_path, the manager given b.bind; (exit code, messages expected on stderr).
NAV = "input nav ${VEHICLE}.NAV nav_solution_t\n"
SETPOINT = "output setpoint ${VEHICLE}.SETPOINT setpoint_t\n"
INCLUDE_CASES = {
    "relative_to_the_includer": (
        {"b.bind": NAV + 'include "shared/s.bind"\n', "shared/s.bind": 'include "../o.bind"\n', "o.bind": SETPOINT},
        None,
        [],
    ),
    "missing": (
        {"b.bind": NAV + 'include  "nope.bind"\n' + SETPOINT},
        1,
        ["b.bind:2:10: cannot include 'nope.bind' (", "nope.bind): No such file or directory"],
    ),
    "a_folder": (
        {"b.bind": NAV + 'include "d"\n' + SETPOINT, "d/x": ""},
        1,
        ["b.bind:2:9: cannot include 'd'", "not a regular file"],
    ),
    "cycle": (
        {"b.bind": NAV + 'include "a.bind"\n' + SETPOINT, "a.bind": '\ninclude "b.bind"\n'},
        1,
        ["a.bind:2:9: include cycle: ", "b.bind -> ", "a.bind -> ", "b.bind\n"],
    ),
    "itself": ({"b.bind": NAV + 'include "b.bind"\n' + SETPOINT}, 1, ["b.bind:2:9: include cycle: "]),
    "no_quotes": ({"b.bind": NAV + "include s.bind\n" + SETPOINT}, 1, ['b.bind:2:9: expected `include "FILE"`']),
    "two_names": (
        {"b.bind": NAV + 'include "s.bind" "t.bind"\n' + SETPOINT},
        1,
        ["b.bind:2:18: one file per include line"],
    ),
    "error_in_the_included_file": (
        {"b.bind": NAV + 'include "s.bind"\n' + SETPOINT, "s.bind": "# shared\ninput gps X.GPS no_such_t\n"},
        1,
        ["s.bind:2:17: unknown message type 'no_such_t'"],
    ),
    "prefix_bound_in_another_file": (
        {"b.bind": NAV + 'include "s.bind"\n' + SETPOINT, "s.bind": "input nav X.NAV2 nav_solution_t\n"},
        1,
        ["s.bind:1:7: prefix 'nav' is already bound at ", "b.bind:1\n"],
    ),
    "too_deep": (
        {"b.bind": NAV + 'include "i1.bind"\n' + SETPOINT}
        | {f"i{k}.bind": f'include "i{k + 1}.bind"\n' for k in range(1, 12)}
        | {"i12.bind": ""},
        1,
        ["i7.bind:1:9: includes nested deeper than 8 files"],
    ),
}


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
@pytest.mark.parametrize("case", list(INCLUDE_CASES))
def test_binding_includes(tmp_path, lcm_url, child_env, sanitized, case):
    files, code, expected = INCLUDE_CASES[case]
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    returncode, stderr = load(tmp_path / "b.bind", lcm_url, child_env, sanitized, expect_running=code is None)
    if code is not None:
        assert returncode == code, stderr
        for part in expected:
            assert part in stderr, stderr

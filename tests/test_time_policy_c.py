"""The time rule as implemented in C (c/common/time_policy.c), driven through
`auv-lcm-probe time` in both builds: valid range, clocks that never run
backwards and follow a jump only when a second message confirms it, data
from the future or out of order. The same cases are in the Python twin's
tests; the numbers are in docs/channels.md, "Time and timestamps"."""

from __future__ import annotations

import subprocess

import pytest
from conftest import c_program

INT64_MIN, INT64_MAX = -(2**63), 2**63 - 1
UTIME_MAX = 4_102_444_800_000_000
S = 1_000_000


def probe(sanitized, *args) -> list[str]:
    p = subprocess.run(
        [c_program("bin/auv-lcm-probe", sanitized), "time", *map(str, args)], capture_output=True, text=True, timeout=30
    )
    assert p.returncode == 0, p.stderr
    return p.stdout.splitlines()


CLOCK_CASES = [
    # values offered in turn -> what each gives
    ([0, 5 * S, 4 * S], ["ok 0", f"ok {5 * S}", "clock backwards"]),
    ([INT64_MIN, -1, INT64_MAX, UTIME_MAX + 1, UTIME_MAX], ["invalid time"] * 4 + [f"ok {UTIME_MAX}"]),
    ([10 * S, 10 * S + 60 * S], ["ok 10000000", "ok 70000000"]),  # exactly the maximum jump
    ([10 * S, 10 * S + 60 * S + 1, 20 * S], ["ok 10000000", "unconfirmed clock jump", "ok 20000000"]),
    ([10 * S, 1000 * S, 1000 * S + S], ["ok 10000000", "unconfirmed clock jump", "ok 1001000000"]),  # confirmed
    ([10 * S, 1000 * S, 999 * S], ["ok 10000000", "unconfirmed clock jump", "unconfirmed clock jump"]),
    (
        [10 * S, 1000 * S, 2000 * S, 2000 * S],
        ["ok 10000000", "unconfirmed clock jump", "unconfirmed clock jump", "ok 2000000000"],
    ),
    (
        [10 * S, 1000 * S, 11 * S, 1001 * S],
        ["ok 10000000", "unconfirmed clock jump", "ok 11000000", "unconfirmed clock jump"],
    ),  # a good tick clears it
]


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
@pytest.mark.parametrize("values,expected", CLOCK_CASES, ids=[f"clock{i}" for i in range(len(CLOCK_CASES))])
def test_clock_rule(sanitized, values, expected):
    assert probe(sanitized, "clock", *values) == expected


INPUT_CASES = [
    # (now, stamps) -> results
    (100 * S, [100 * S, 101 * S, 101 * S + 1], ["ok", "ok", "from the future"]),
    (100 * S, [INT64_MIN, -1, INT64_MAX, 10**18, UTIME_MAX + 1], ["invalid time"] * 5),
    (100 * S, [50 * S, 40 * S, 50 * S, 60 * S], ["ok", "out of order", "ok", "ok"]),
    (UTIME_MAX, [UTIME_MAX, UTIME_MAX - 1], ["ok", "out of order"]),
]


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
@pytest.mark.parametrize("now,stamps,expected", INPUT_CASES, ids=[f"input{i}" for i in range(len(INPUT_CASES))])
def test_input_rule(sanitized, now, stamps, expected):
    assert probe(sanitized, "input", now, S, *stamps) == expected


def test_help_and_old_url_spelling():
    p = subprocess.run([c_program("bin/auv-lcm-probe"), "--help"], capture_output=True, text=True, timeout=30)
    assert p.returncode == 0 and "--lcm-url" in p.stdout

"""The timestamp rule for Python receivers (auvlcm.timepolicy): a hostile corpus of
stamps against the clock gate and the data-input gate. Pure, no LCM."""

from __future__ import annotations

import pytest

from auvlcm.timepolicy import MAX_CLOCK_JUMP_US, UTIME_MAX, ClockGate, InputGate, TimeDrops, valid_utime

INT64_MAX, INT64_MIN = 2**63 - 1, -(2**63)
HOSTILE = [INT64_MAX, INT64_MIN, -1, 10**18, UTIME_MAX + 1, 2**64]


def drops() -> tuple[TimeDrops, list[str]]:
    lines: list[str] = []
    return TimeDrops("test", lines.append), lines


@pytest.mark.parametrize("stamp", HOSTILE)
def test_stamps_outside_the_valid_range_never_reach_a_clock(stamp):
    d, lines = drops()
    gate = ClockGate(d)
    assert not gate.offer(stamp, 1)
    assert gate.now is None and d.counts["invalid"] == 1
    assert gate.offer(5_000_000, 1) and gate.now == 5_000_000
    assert not gate.offer(stamp, 1)
    assert gate.now == 5_000_000 and d.counts["invalid"] == 2
    assert len(lines) == 1 and "invalid" in lines[0]  # logged once


def test_valid_range_ends():
    assert valid_utime(0) and valid_utime(UTIME_MAX)
    assert not valid_utime(-1) and not valid_utime(UTIME_MAX + 1) and not valid_utime(1.5)


def test_a_clock_never_runs_backwards_and_repeats_are_fine():
    d, _ = drops()
    gate = ClockGate(d)
    assert gate.offer(1_000_000, 1)
    assert gate.offer(1_000_000, 1)  # a lockstep repeat
    assert not gate.offer(999_999, 1)
    assert gate.now == 1_000_000 and d.counts["regression"] == 1


def test_a_clock_of_an_older_term_is_refused_even_when_ahead():
    d, _ = drops()
    gate = ClockGate(d)
    assert gate.offer(10_000_000, 1)
    assert gate.offer(10_100_000, 2)  # the next term: at once
    assert not gate.offer(10_200_000, 1)  # the old server resumed
    assert gate.now == 10_100_000 and gate.term == 2 and d.counts["old_term"] == 1


def test_a_known_term_refuses_older_clocks_before_its_first_clock():
    d, _ = drops()
    gate = ClockGate(d)
    gate.offer(1_000_000, 3)
    gate.raise_term(4)  # its server's heartbeat was heard
    assert not gate.offer(1_100_000, 3)
    assert gate.offer(1_200_000, 4)


def test_one_jump_is_refused_a_confirmed_jump_is_followed():
    d, _ = drops()
    gate = ClockGate(d)
    assert gate.offer(1_000_000, 1)
    far = 2_000_000 + MAX_CLOCK_JUMP_US
    assert not gate.offer(far, 1) and d.counts["jump"] == 1
    assert gate.offer(1_100_000, 1)  # the bad one stopped nothing
    assert not gate.offer(far, 1)
    assert gate.offer(far + 100_000, 1)  # the second message confirms it
    assert gate.now == far + 100_000


def test_one_bad_message_cannot_throw_time_forward_whatever_follows():
    d, _ = drops()
    gate = ClockGate(d)
    gate.offer(1_000_000, 1)
    assert not gate.offer(UTIME_MAX, 1)
    for k in range(1, 20):
        assert gate.offer(1_000_000 + k * 100_000, 1)
    assert gate.now == 2_900_000


def test_a_term_far_ahead_needs_confirmation():
    d, _ = drops()
    gate = ClockGate(d)
    gate.offer(1_000_000, 1)
    assert not gate.offer(1_100_000, 2**31 - 1)  # one corrupt term cannot lock the clock out
    assert gate.offer(1_200_000, 1)
    assert not gate.offer(1_300_000, 7)  # a node that missed elections...
    assert gate.offer(1_400_000, 7) and gate.term == 7  # ...is followed one message later


def test_data_from_the_future_and_out_of_order_is_dropped():
    d, lines = drops()
    gate = InputGate(d, "AUV1.ACTUATORS")
    now = 10_000_000
    assert gate.offer(now + 1_000_000, now)  # within the tolerance
    assert not gate.offer(now + 1_000_001, now)
    assert not gate.offer(now, now)  # older than the newest accepted
    for s in HOSTILE:
        assert not gate.offer(s, now)
    assert d.counts["future"] == 1 and d.counts["out_of_order"] == 1
    assert d.counts["invalid"] == len(HOSTILE)
    assert len(lines) == 3 and all("AUV1.ACTUATORS" in line for line in lines)
    assert d.summary() == f"time drops: invalid {len(HOSTILE)}, future 1, out_of_order 1"


def test_data_held_before_the_clock_is_judged_once_it_has_one():
    d, _ = drops()
    gate = InputGate(d, "x")
    assert gate.offer(10**15, None)  # no clock yet: held
    assert not gate.judge_held(5_000_000) and d.counts["future"] == 1
    assert gate.offer(5_000_000, 5_000_000)  # and it no longer blocks newer values


@pytest.mark.parametrize("first", [(4_000_000_000_000_000, 1), (1_000_000, 2**31 - 1)])
def test_a_corrupt_first_clock_cannot_stop_time(first):
    """Nothing to compare the first value with: it is taken, provisionally. Two
    consistent messages that contradict it replace it; then the rule holds again."""
    d, _ = drops()
    gate = ClockGate(d)
    assert gate.offer(*first)
    assert not gate.offer(2_000_000, 1)  # contradicts it: held, counted
    assert gate.offer(2_100_000, 1)  # confirmed: the clock is back on its line
    assert gate.now == 2_100_000 and gate.term == 1
    assert not gate.offer(2_000_000, 1)  # and never backwards again
    assert not gate.offer(1_000_000, 1)


def test_a_good_first_clock_is_confirmed_by_the_next():
    d, _ = drops()
    gate = ClockGate(d)
    assert gate.offer(1_000_000, 1) and gate.offer(1_100_000, 1)
    assert not gate.offer(500_000, 1) and not gate.offer(600_000, 1)  # no longer provisional
    assert gate.now == 1_100_000

"""sim.periodic.Periodic: an output's fixed grid of due times, missed slots skipped."""

from __future__ import annotations

from sim.periodic import Periodic


def test_slots_stay_on_the_grid_whatever_the_step():
    p = Periodic(0.1, 0.05)
    seen = []
    for k in range(1, 100):
        t = k * 0.03  # a step that is no divisor of the period
        if p.due(t):
            seen.append(t)
            p.advance(t)
    # one sample per slot 0.05 + k 0.1, at the first step at or after it: no drift
    assert len(seen) == 30 and abs(p.next_t - 3.05) < 1e-9
    assert all(-1e-9 <= t - (0.05 + 0.1 * k) < 0.03 for k, t in enumerate(seen))


def test_missed_slots_are_skipped_not_caught_up():
    p = Periodic(0.1)
    assert p.due(0.0)
    p.advance(0.55)  # five slots went by unseen
    assert abs(p.next_t - 0.6) < 1e-12 and not p.due(0.59)


def test_a_rounding_error_short_of_a_slot_is_due():
    p = Periodic(0.1, 0.3)
    assert p.due(0.1 + 0.2)  # 0.30000000000000004 > 0.3, and the other way round
    assert Periodic(0.1, 0.1 + 0.2).due(0.3)


def test_restart_starts_the_grid_there():
    p = Periodic(1.0, 1.0)
    p.restart(12.5)
    assert not p.due(12.4) and p.due(12.5)
    p.advance(12.5)
    assert p.next_t == 13.5

"""auv-nav under the time rule (docs/channels.md, "Time and timestamps";
issue 12 item 3): sensor messages stamped out of range, from the future or
out of order, and clock values that are invalid, backwards or an unconfirmed
jump are counted per reason in NAV_STATUS and dropped; the filter's time and
its output never move with them."""

from __future__ import annotations

import signal
import subprocess

import pytest
from lcm_proc import stop
from test_nav_process import NAV_CFG, World

from auv import depth_t, sim_clock_t
from auvlcm import programs

INT64_MIN, INT64_MAX = -(2**63), 2**63 - 1


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_bad_stamps_are_counted_in_nav_status_and_dropped(lcm_url, child_env, sanitized, build_dir):
    variant = build_dir / "san" if sanitized else build_dir
    nav = subprocess.Popen(
        programs.auv_nav(variant, config=NAV_CFG, vehicle="AUV1", lcm_url=lcm_url),
        stderr=subprocess.PIPE,
        text=True,
        env=child_env,
    )
    try:
        w = World(lcm_url)
        w.drain(1.0)
        w.run(2, gps=True)

        def depth(utime: int) -> None:
            d = depth_t()
            d.depth_m, d.valid, d.vehicle, d.utime = 5.0, True, "AUV1", utime
            w.lc.publish("AUV1.DEPTH", d.encode())

        for bad in (INT64_MIN, -1, 10**18, INT64_MAX):
            depth(bad)  # invalid: 4
        depth(w.t + 30_000_000)  # 30 s ahead of the clock: from the future
        depth(w.t - 2_000_000)  # older than the newest depth: out of order
        for bad in (INT64_MAX, INT64_MIN):
            c = sim_clock_t()
            c.utime = bad
            w.lc.publish("SIM.CLOCK", c.encode())
        c = sim_clock_t()
        c.utime = w.t - 500_000
        w.lc.publish("SIM.CLOCK", c.encode())  # backwards
        c.utime = w.t + 600_000_000
        w.lc.publish("SIM.CLOCK", c.encode())  # a 10-minute jump, never confirmed
        w.run(2.5, gps=True)
        w.drain()
        s = w.status[-1]
        assert (s.dropped_invalid_time, s.dropped_future, s.dropped_out_of_order) == (4, 1, 1), {
            k: getattr(s, k) for k in s.__slots__
        }
        assert (s.clock_invalid, s.clock_backwards, s.clock_jumps) == (2, 1, 1), {k: getattr(s, k) for k in s.__slots__}
        assert s.utime <= w.t, "the filter's clock followed a refused value"
        assert w.nav and max(n.utime for n in w.nav) <= w.t
    finally:
        rc = stop(nav, signal.SIGTERM)
    err = nav.stderr.read()
    assert rc == 0, err
    assert "(from the future); further drops of this kind are only counted" in err
    assert "time rule drops: invalid time 4, from the future 1, out of order 1" in err

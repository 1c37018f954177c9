"""auv-front-estimate as a process over LCM: this test is the global clock and
the vehicle (its navigation and its CTD), flying a zig-zag at 4 m/s across a
straight front of the estimator's own model (docs/sampling.md); bad readings of
every kind among the good ones, each counted by its reason; the estimates say
TOO_FEW (with NaN parameters) until both waters are seen, then OK with the
front's parameters within their sigmas. A teammate's front summary in a
team-link frame (and a frame that does not decode): the team's estimate
(FRONT_TEAM) is the teammate's while the vehicle has seen one water only, and
tighter than its own at the end; a clean stop."""

from __future__ import annotations

import math
import random
import signal
import subprocess

import lcm
import pytest
from lcm_proc import pump, stop

from auv import ctd_t, front_estimate_t, modem_rx_t, modem_tx_t, nav_solution_t, sim_clock_t
from auvlcm import programs
from auvlcm.team_codec import TeamCodec

# the front: along 0.2 rad from north, 300 m right of the origin, 16 degC left of it, 12 right, 20 m wide
OFFSET, ANGLE, TA, TB, WIDTH = 300.0, 0.2, 16.0, 12.0, 20.0
STEP_US = 100_000  # the clock, the navigation and the CTD at 10 Hz of sim time
SPEED = 4.0  # m/s: 0.4 m between readings
# what AUV2 tells the team of its own estimate (the summary's fields, c/plugins/team/team_link.schema)
SUMMARY = {
    "vehicle": 1,
    "time_s": 4,
    "offset_m": 300.5,
    "angle": 0.2,
    "temp_a_c": 16.0,
    "temp_b_c": 12.0,
    "width_m": 20.5,
    "offset_sigma_m": 0.5,
    "angle_sigma": 0.005,
    "temp_sigma_c": 0.01,
    "width_sigma_m": 0.5,
    "samples": 400,
}


def water(n: float, e: float) -> float:
    r = -n * math.sin(ANGLE) + e * math.cos(ANGLE)
    return TA + (TB - TA) * 0.5 * (1.0 + math.tanh((r - OFFSET) / WIDTH))


def path(k: int) -> tuple[float, float]:
    """The zig-zag at step k: legs at 60 degrees to the front, 60 m either side of it,
    starting 60 m left of it (all in water a until the first crossing)."""
    d = SPEED * k * STEP_US / 1e6
    leg = 120.0 / math.sin(math.radians(60))  # from one side to the other
    s = d * math.cos(math.radians(60)) - 150.0
    phase = (d % (2 * leg)) / leg
    r = OFFSET - 60.0 + 120.0 * (phase if phase <= 1.0 else 2.0 - phase)
    return s * math.cos(ANGLE) - r * math.sin(ANGLE), s * math.sin(ANGLE) + r * math.cos(ANGLE)


@pytest.fixture
def estimator(variant_dir, lcm_url, child_env):
    proc = subprocess.Popen(
        programs.auv_front_estimate(variant_dir, vehicle="AUV1", lcm_url=lcm_url, rate_hz=1.0),
        stderr=subprocess.PIPE,
        text=True,
        env=child_env,
    )
    yield proc
    stop(proc, signal.SIGTERM)


def test_estimates_over_lcm_with_bad_readings_counted(estimator, lcm_url):
    lc = lcm.LCM(lcm_url)
    got: list[front_estimate_t] = []
    team: list[front_estimate_t] = []
    lc.subscribe("AUV1.FRONT_ESTIMATE", lambda c, d: got.append(front_estimate_t.decode(d)))
    lc.subscribe("AUV1.FRONT_TEAM", lambda c, d: team.append(front_estimate_t.decode(d)))
    for _ in range(20):  # let it subscribe
        lc.handle_timeout(50)
    rng = random.Random(5)
    bad = {"not_valid": 0, "out_of_range": 0, "below_layer": 0, "no_position": 0, "time_rule": 0}
    steps = 1300  # 130 s: 520 m of path, 4 crossings
    for k in range(1, steps + 1):
        t = k * STEP_US
        n, e = path(k)
        gap = 600 <= k < 630  # 3 s without navigation: its readings have no position
        if not gap:
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.north_m, nav.east_m, nav.depth_m = t, "AUV1", n, e, 5.0
            lc.publish("AUV1.NAV", nav.encode())
        c = ctd_t()
        c.utime, c.vehicle, c.valid, c.depth_m = t, "AUV1", True, 5.0
        c.temperature_c = water(n, e) + rng.gauss(0.0, 0.02)
        kind = k % 50
        if kind == 10:
            c.valid = False
            bad["not_valid"] += 1
        elif kind == 20:
            c.temperature_c = float("nan")
            bad["out_of_range"] += 1
        elif kind == 30:
            c.temperature_c = 99.0
            bad["out_of_range"] += 1
        elif kind == 40:
            c.depth_m = 30.0
            bad["below_layer"] += 1
        elif gap:
            bad["no_position"] += 1
        lc.publish("AUV1.CTD", c.encode())
        if k == 700:  # from 10 min in the future: the time rule drops it
            f = ctd_t()
            f.utime, f.vehicle, f.valid, f.depth_m, f.temperature_c = t + 600_000_000, "AUV1", True, 5.0, 14.0
            lc.publish("AUV1.CTD", f.encode())
            bad["time_rule"] += 1
        if k in (50, 51):  # AUV2's summary, then AUV3's frame cut short inside a message
            rx = modem_rx_t()
            rx.utime, rx.vehicle, rx.kind = t, "AUV1", modem_tx_t.KIND_TEAM
            rx.src_vehicle = "AUV2" if k == 50 else "AUV3"
            payload = TeamCodec().encode_frame([("front", SUMMARY)], 32)
            rx.payload = payload if k == 50 else payload[:5]
            rx.n_bytes = len(rx.payload)
            lc.publish("AUV1.MODEM_RX", rx.encode())
        clock = sim_clock_t()
        clock.utime, clock.mode, clock.step_us = t, sim_clock_t.MODE_LOCKSTEP, STEP_US
        lc.publish("SIM.CLOCK", clock.encode())
        lc.handle_timeout(0)
        if k % 10 == 0:  # each second, the estimate due in it (its first at the first tick, then 1 s apart)
            assert pump(lc, lambda: bool(got) and got[-1].utime >= t - 1_000_000 + STEP_US, timeout=20), (
                t,
                got[-1].utime if got else None,
            )
    t_end = steps * STEP_US
    assert got, estimator.stderr
    # the team's estimate of the same cycle comes right after the vehicle's own
    assert pump(lc, lambda: bool(team) and team[-1].utime >= got[-1].utime, timeout=10)
    first = got[0]
    assert first.status == front_estimate_t.STATUS_TOO_FEW and math.isnan(first.offset_m), first.status_text
    assert all(
        all(math.isfinite(v) for v in (m.offset_m, m.angle_rad, m.width_m, m.offset_sigma_m))
        for m in got
        if m.status == front_estimate_t.STATUS_OK
    )
    last = got[-1]
    assert last.utime >= t_end - 1_000_000, last.utime
    assert last.status == front_estimate_t.STATUS_OK, last.status_text
    print(
        f"\nestimate at {last.utime / 1e6:.0f} s from {last.samples_used} bins ({last.readings_used} readings): "
        f"offset {last.offset_m:.2f} +- {last.offset_sigma_m:.2f} m, angle {last.angle_rad:.4f} +- "
        f"{last.angle_sigma_rad:.4f} rad, Ta {last.temperature_a_c:.3f} +- {last.temperature_a_sigma_c:.3f}, "
        f"Tb {last.temperature_b_c:.3f} +- {last.temperature_b_sigma_c:.3f}, width {last.width_m:.2f} +- "
        f"{last.width_sigma_m:.2f} m; rms {last.residual_rms_c:.3f} degC; {last.status_text}"
    )
    for value, sigma, truth in (
        (last.offset_m, last.offset_sigma_m, OFFSET),
        (last.angle_rad, last.angle_sigma_rad, ANGLE),
        (last.temperature_a_c, last.temperature_a_sigma_c, TA),
        (last.temperature_b_c, last.temperature_b_sigma_c, TB),
        (last.width_m, last.width_sigma_m, WIDTH),
    ):
        assert abs(value - truth) < 4 * sigma, (value, sigma, truth)
    assert not last.meander and last.amplitude_m == 0.0 and math.isnan(last.wavelength_m)
    assert last.dropped_not_valid == bad["not_valid"]
    assert last.dropped_out_of_range == bad["out_of_range"]
    assert last.dropped_below_layer == bad["below_layer"]
    assert last.dropped_time_rule == bad["time_rule"]
    # the gap's readings, less its bad ones; the last reading of the gap may be placed
    # between the solutions either side of it only if they are 2 s apart or less: they are 3 s
    assert last.dropped_no_position == bad["no_position"]
    assert last.dropped_too_old == 0
    # the team's estimate: the teammate's summary alone while the vehicle had one water
    early = next(m for m in team if m.utime >= 6_000_000)
    own_early = next(m for m in got if m.utime == early.utime)
    assert own_early.status == front_estimate_t.STATUS_TOO_FEW and own_early.peers_used == 0
    assert early.status == front_estimate_t.STATUS_OK and early.peers_used == 1, early.status_text
    assert abs(early.offset_m - SUMMARY["offset_m"]) < 0.6 and abs(early.width_m - SUMMARY["width_m"]) < 1.0
    # ... and at the end, its own samples and the summary: tighter than its own
    t_last = next(m for m in reversed(team) if m.utime == last.utime)
    print(
        f"team estimate at {t_last.utime / 1e6:.0f} s: offset {t_last.offset_m:.2f} +- {t_last.offset_sigma_m:.3f} m "
        f"(own {last.offset_sigma_m:.3f}); {t_last.status_text}"
    )
    assert t_last.status == front_estimate_t.STATUS_OK and t_last.peers_used == 1
    assert t_last.offset_sigma_m <= last.offset_sigma_m and abs(t_last.offset_m - OFFSET) < 4 * t_last.offset_sigma_m
    rc = stop(estimator, signal.SIGINT)
    err = estimator.stderr.read()
    assert rc == 0, err
    assert "TOO_FEW" in err and ": OK: straight front" in err and "estimates published" in err
    assert "a front summary from AUV2" in err and "summaries heard 1, team frames that did not decode 1" in err

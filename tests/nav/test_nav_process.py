"""auv-nav as a process: bad configuration and options, alignment as seen on
LCM, undecodable and absurd messages counted and dropped, clean stop. The
test is the global clock and the vehicle's sensors here (a stationary vehicle
at 5 m), so every step is deterministic."""

from __future__ import annotations

import math
import random
import signal
import subprocess

import lcm
import pytest
from conftest import ROOT
from lcm_proc import stop
from lcm_samples import random_message

from auv import (
    ahrs_t,
    depth_t,
    dvl_t,
    gps_fix_t,
    lbl_ranges_t,
    nav_filter_status_t,
    nav_solution_t,
    process_health_t,
    sim_clock_t,
)
from auvlcm import programs

NAV_CFG = ROOT / "missions" / "nav" / "remus100_survey.nav"
BAD = """compass_noise_rad 0.01
depht_noise_m 0.1
transponder 1 0 0
"""


@pytest.mark.parametrize("program", ["auv-nav", "auv-nav-replay"])
def test_bad_config_is_reported_with_file_line_and_column(tmp_path, variant_dir, program, child_env):
    cfg = tmp_path / "bad.nav"
    cfg.write_text(BAD)
    extra = ["--log", tmp_path / "none"] if program == "auv-nav-replay" else []
    p = subprocess.run(
        [variant_dir / "bin" / program, "--config", cfg, *extra],
        capture_output=True,
        text=True,
        timeout=30,
        env=child_env,
    )
    assert p.returncode == 1, p.stderr
    lines = p.stderr.splitlines()
    assert f"{cfg}:2:1: unknown key 'depht_noise_m' (did you mean 'depth_noise_m'?)" in lines
    assert f"{cfg}:3:1: transponder needs 5 values: ID NORTH_M EAST_M DEPTH_M TURNAROUND_S" in lines


@pytest.mark.parametrize(
    "args,code",
    [([], 2), (["--config"], 2), (["--config", "x", "--rate", "0"], 2), (["--config", "x", "--clock", "gps"], 2)],
)
def test_usage_errors_exit_2(variant_dir, args, code, child_env):
    p = subprocess.run(
        [variant_dir / "bin" / "auv-nav", *args], capture_output=True, text=True, timeout=30, env=child_env
    )
    assert p.returncode == code and p.stderr


def test_replay_rejects_a_bad_drop_and_a_missing_log(tmp_path, build_dir):
    exe = build_dir / "bin" / "auv-nav-replay"
    p = subprocess.run(
        [exe, "--config", NAV_CFG, "--log", tmp_path / "x", "--drop", "sonar"],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert p.returncode == 1 and "--drop" in p.stderr
    p = subprocess.run(
        [exe, "--config", NAV_CFG, "--log", tmp_path / "missing.lcmlog"], capture_output=True, text=True, timeout=30
    )
    assert p.returncode == 1 and "cannot open log" in p.stderr


class World:
    """The clock and the sensors of a vehicle resting at (10, 20, 5 m), heading 90 deg."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.t = 0
        self.nav, self.status, self.health = [], [], []
        self.lc.subscribe("AUV1.NAV", lambda c, d: self.nav.append(nav_solution_t.decode(d)))
        self.lc.subscribe("AUV1.NAV_STATUS", lambda c, d: self.status.append(nav_filter_status_t.decode(d)))
        self.lc.subscribe("AUV1.HEALTH", lambda c, d: self.health.append(process_health_t.decode(d)))

    def pub(self, channel: str, msg) -> None:
        msg.utime, msg.vehicle = self.t, "AUV1"
        self.lc.publish(channel, msg.encode())

    def step(self, gps: bool) -> None:
        """0.05 s of sensors, then the clock."""
        self.t += 50000
        a = ahrs_t()
        a.heading_rad, a.valid = math.pi / 2, True
        self.pub("AUV1.AHRS", a)
        if self.t % 100000 == 0:
            d = depth_t()
            d.depth_m, d.valid = 5.0, True
            self.pub("AUV1.DEPTH", d)
        if self.t % 200000 == 0:
            v = dvl_t()
            v.mode, v.velocity_mps, v.velocity_sigma_mps, v.altitude_m = dvl_t.MODE_BOTTOM_LOCK, [0, 0, 0], 0.01, 20
            v.beam_range_m = [20.0] * 4
            self.pub("AUV1.DVL", v)
        if gps and self.t % 1000000 == 0:
            g = gps_fix_t()
            g.fix_type, g.north_m, g.east_m, g.horizontal_sigma_m = gps_fix_t.FIX_3D, 10.0, 20.0, 2.0
            self.pub("AUV1.GPS", g)
        c = sim_clock_t()
        c.utime, c.mode = self.t, sim_clock_t.MODE_LOCKSTEP
        self.lc.publish("SIM.CLOCK", c.encode())
        self.lc.handle_timeout(5)

    def run(self, seconds: float, gps: bool) -> None:
        for _ in range(int(seconds * 20)):
            self.step(gps)

    def drain(self, seconds: float = 0.5) -> None:
        for _ in range(int(seconds / 0.05)):
            self.lc.handle_timeout(50)


def test_live_alignment_bad_messages_and_clean_stop(variant_dir, lcm_url, child_env):
    nav = subprocess.Popen(
        programs.auv_nav(variant_dir, config=NAV_CFG, vehicle="AUV1", lcm_url=lcm_url),
        stderr=subprocess.PIPE,
        text=True,
        env=child_env,
    )
    try:
        w = World(lcm_url)
        w.drain(1.0)  # let it subscribe (liblcm's self-test)
        w.run(3, gps=False)  # compass, depth, DVL but no position
        w.drain()
        assert w.nav == [], "no solution before the filter is aligned"
        assert w.status and not any(s.trusted for s in w.status)
        w.run(3, gps=True)
        w.drain()
        assert w.nav, nav.stderr
        last = w.nav[-1]
        assert last.source == nav_solution_t.SOURCE_EKF and last.status & nav_solution_t.STATUS_ALIGNED
        assert abs(last.north_m - 10) < 3 and abs(last.east_m - 20) < 3 and abs(last.depth_m - 5) < 0.1
        assert abs(last.heading_rad - math.pi / 2) < 0.01
        assert abs(last.altitude_m - 20) < 0.01  # the DVL's range to the bottom
        assert w.status[-1].trusted
        # garbage: a truncated DVL, an AHRS on the GPS channel, and seeded
        # random (absurd) messages of every sensor type
        w.lc.publish("AUV1.DVL", dvl_t().encode()[:-3])
        w.lc.publish("AUV1.GPS", ahrs_t().encode())
        rng = random.Random(8)
        for cls, ch in (
            (ahrs_t, "AHRS"),
            (depth_t, "DEPTH"),
            (dvl_t, "DVL"),
            (gps_fix_t, "GPS"),
            (lbl_ranges_t, "LBL"),
        ):
            for _ in range(20):
                m = random_message(cls, rng)
                m.vehicle = "AUV1"
                w.lc.publish(f"AUV1.{ch}", m.encode())
        w.run(3, gps=True)
        w.drain()
        assert w.health[-1].decode_errors == 2 and w.health[-1].process == "NAV"
        last = w.nav[-1]
        assert last.status & nav_solution_t.STATUS_ALIGNED and not last.status & nav_solution_t.STATUS_INVALID
        assert abs(last.north_m - 10) < 3 and abs(last.east_m - 20) < 3 and abs(last.depth_m - 5) < 0.5
        assert all(math.isfinite(x) for x in (last.north_m, last.east_m, last.position_cov_m2[0][0]))
    finally:
        rc = stop(nav, signal.SIGTERM)
    err = nav.stderr.read()
    assert rc == 0, err
    assert "decode errors 2" in err and "numeric resets 0" in err

"""A survey flown on the onboard filter's output, closed loop over real LCM:
the simulator (missions/sim/remus100.yaml, its INS moved to AUV1.NAV_INS),
auv-nav publishing AUV1.NAV and AUV1.NAV_STATUS, and the PILOT and NAVIGATOR
managers bound to them, flying missions/nav/box_survey_ekf.chasm (the box
survey with abort rules on the filter's trust). Lockstep with this process's
global clock (tests/missions/closed_loop.py), which also waits for the
filter's solution of each tick. A second run shows a plan aborting on the
filter's own uncertainty."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest
from closed_loop import MISSIONS, TICK_US, Mission, Record
from conftest import BUILD

from auv import chasm_status_t, nav_filter_status_t, nav_solution_t
from auvlcm import programs

PLAN = MISSIONS / "nav" / "box_survey_ekf.chasm"
NAVCONF = ("-m", "tools.nav.navconf")
# As tests/missions/test_missions.py: calm sea (the pilot's dive from the
# surface in the default yaw-unstable hull does not survive the swell).
SIM = {"environment": {"waves": None}, "sensors": {"ins": {"channel": "NAV_INS"}}}
BOX = dict(north=40.0, east=-15.0, length=200.0, width=60.0)  # box_survey.chasm


class EkfMission(Mission):
    """A Mission whose navigator and pilot fly on auv-nav's solution."""

    def __init__(self, tmp, url, env, plan, params=None) -> None:
        super().__init__(tmp, url, env, plan, params, sim=SIM)
        self.bind = MISSIONS / "bindings" / "navigator_ekf.bind"
        self.nav_cfg = tmp / "auv1.nav"
        subprocess.run([sys.executable, *NAVCONF, self.sim_cfg, "-o", self.nav_cfg], check=True, env=env, timeout=60)
        self.sources: set[int] = set()
        self.trusted: list[tuple[float, bool, float]] = []
        self.ins: list[tuple[float, float, float]] = []
        self.rx.subscribe("AUV1.NAV", nav_solution_t, lambda c, m: self.sources.add(m.source), 1000)
        self.rx.subscribe(
            "AUV1.NAV_STATUS",
            nav_filter_status_t,
            lambda c, m: self.trusted.append((m.utime / 1e6, m.trusted, m.position_sigma_m)),
            100,
        )
        self.rx.subscribe(
            "AUV1.NAV_INS", nav_solution_t, lambda c, m: self.ins.append((m.utime / 1e6, m.north_m, m.east_m)), 1000
        )

    def __enter__(self) -> "EkfMission":
        self._start(
            "nav",
            programs.auv_nav(BUILD, config=self.nav_cfg, vehicle="AUV1", lcm_url=self.url, rate_hz=20),
            "auv-nav: AUV1",
        )
        return super().__enter__()

    def _cycled(self) -> bool:
        # once aligned, the filter's solution for the compass message of this
        # tick is in before the next (the simulator stamps its messages with
        # its step time, which can be 1 us short of the tick's)
        fresh = not self.rec.nav or self.rec.nav[-1].t * 1e6 >= self.utime - TICK_US - 1000
        return fresh and super()._cycled()


def _truth_at(rec: Record, t: float):
    return min(rec.truth[max(0, int(t * 50) - 60) : int(t * 50) + 60] or rec.truth, key=lambda p: abs(p.t - t))


def _done(rec: Record) -> bool:
    return (
        rec.run_state in (chasm_status_t.RUN_DONE, chasm_status_t.RUN_ABORTED)
        and rec.leaf() in ("recover", "emergency")
        and rec.truth[-1].depth < 0.5
    )


@pytest.mark.slow
def test_box_survey_flown_on_the_filter(tmp_path, lcm_url, child_env):
    with EkfMission(tmp_path, lcm_url, child_env, PLAN) as m:
        rec = m.fly(_done, max_sim_s=900)
    leaves = [s[1] for s in rec.states]
    assert rec.run_state == chasm_status_t.RUN_DONE and leaves[-1] == "recover", rec.states
    assert "emergency" not in leaves
    assert m.sources == {nav_solution_t.SOURCE_EKF}
    assert sum(1 for s in rec.states if s[1] == "gps_fix") >= 2
    # what the vehicle believed against where it was
    errs = [math.hypot(p.n - t.n, p.e - t.e) for p in rec.nav[::10] for t in [_truth_at(rec, p.t)]]
    rms = math.sqrt(sum(e * e for e in errs) / len(errs))
    print(f"\nfilter vs truth over the survey: rms {rms:.2f} m, max {max(errs):.2f} m ({len(errs)} samples)")
    assert rms < 2.0 and max(errs) < 6.0
    assert sum(t for _, t, _ in m.trusted) > 0.9 * len(m.trusted)
    # the box was covered: every 10 m of each line's middle within 5 m of the truth track
    for east in (0.0, 30.0):
        bins = {
            int((p.n - BOX["north"]) // 10)
            for p in rec.truth
            if abs(p.e - east) < 5 and BOX["north"] <= p.n < BOX["north"] + BOX["length"]
        }
        assert bins == set(range(20)), f"line at east {east}: gaps at {sorted(set(range(20)) - bins)}"


def test_a_plan_aborts_when_the_filter_is_too_uncertain(tmp_path, lcm_url, child_env):
    """With a 1 m limit on the filter's horizontal sigma (a 2 m GPS never gets
    it there), the plan's nav_uncertain rule fires and the vehicle surfaces."""
    with EkfMission(tmp_path, lcm_url, child_env, PLAN, params={"max_nav_sigma": "1 m"}) as m:
        rec = m.fly(lambda r: r.run_state == chasm_status_t.RUN_ABORTED or r.leaf() == "emergency", max_sim_s=120)
    hit = rec.entered("emergency")
    assert hit is not None and "nav_uncertain" in hit[2], rec.states
    assert hit[0] < 30.0
    assert m.trusted and min(s for _, _, s in m.trusted) > 1.0

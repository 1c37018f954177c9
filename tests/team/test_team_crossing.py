"""Deconfliction and the shared schedule, full stack (issue 15), on the
planner's team plans (tests/team/small_team.py) with their lines changed:

- two search vehicles whose lines cross at the same depth at the same time:
  keep_clear, from the teammate's status heard over the modem, takes one of
  them out of the other's depth band while they pass;
- a misconfigured schedule (two vehicles given the same TDMA slot): their
  frames overlap at the third vehicle, which counts them as collided and
  decodes neither, and each of the two is deaf to the other while it sends."""

from __future__ import annotations

import numpy as np
import small_team as st

# Both lines start at the planner's dive points (0, 8.5) and (0, 63.5) and run
# diagonally (45 degrees either side of north): they cross at (27.5, 36.0),
# 38.9 m from either start, which both vehicles reach at about the same time.
CROSSING_LINES = "0: 0,8.5 80,88.5; 1: 0,63.5 80,-16.5"


def truth(log, vid):
    rows = [(m.utime, m.eta[0], m.eta[1], m.eta[2]) for _, m in st.messages(log, f"{vid}.TRUTH")]
    return {r[0]: r[1:] for r in rows}


def test_crossing_paths_keep_their_separation(tmp_path, lcm_url, child_env):
    base = st.plan(tmp_path / "pair", search=2, ri=0)
    crossing = {v: {"lines": f'"{CROSSING_LINES}"', "linger": "10 s"} for v in ("AUV1", "AUV2")}
    sc = st.variant(base, tmp_path / "crossing.yaml", params=crossing)
    st.fly(sc, tmp_path / "run", lcm_url, child_env)
    log = tmp_path / "run" / "run.lcmlog"
    a, b = truth(log, "AUV1"), truth(log, "AUV2")
    both = sorted(a.keys() & b.keys())
    pa, pb = np.array([a[t] for t in both]), np.array([b[t] for t in both])
    horizontal = np.hypot(pa[:, 0] - pb[:, 0], pa[:, 1] - pb[:, 1])
    vertical = np.abs(pa[:, 2] - pb[:, 2])
    # the paths did cross: at some moment the two were close in the plane ...
    assert horizontal.min() < 10.0, horizontal.min()
    # ... and whenever they were, they were apart in depth (band 3 m)
    close = horizontal < 10.0
    assert vertical[close].min() >= 2.0, (float(vertical[close].min()), int(close.sum()))
    ev = st.team_events(log)
    kc = [e for e in ev if e[2] == "KEEP_CLEAR"]
    assert kc and {e[3] for e in kc} <= {"AUV1", "AUV2"}, kc
    # a manoeuvre, not a standing offset: once they are well apart again
    # (30-45 s after the closest approach), both are back at the plan's 5 m
    t = np.array(both)
    after = (t > t[int(np.argmin(horizontal))] + 30e6) & (t < t[int(np.argmin(horizontal))] + 45e6)
    assert after.sum() > 100
    assert np.median(np.abs(pa[after, 2] - 5.0)) < 0.7 and np.median(np.abs(pb[after, 2] - 5.0)) < 0.7, (
        np.median(pa[after, 2]),
        np.median(pb[after, 2]),
    )


def test_two_vehicles_in_one_slot_collide_at_the_third(tmp_path, lcm_url, child_env):
    base = st.plan(tmp_path / "small")
    sc = st.variant(base, tmp_path / "one_slot.yaml", params={"AUV2": {"my_slot": "0"}}, limit_s=90)
    st.fly(sc, tmp_path / "run", lcm_url, child_env, expect_rc=6)  # the time limit ends it
    link = st.report(tmp_path / "run", tmp_path / "report", child_env)["team"]["link"]["per_vehicle"]
    # AUV1 and AUV2 send in slot 0 together: at AUV3 their frames overlap
    assert link["AUV3"]["collided"] >= 3, link["AUV3"]
    # and each, sending, cannot hear the other (half duplex)
    assert link["AUV1"]["deaf"] >= 3 and link["AUV2"]["deaf"] >= 3, (link["AUV1"], link["AUV2"])
    # AUV3's own slot is clear: both hear it
    assert link["AUV1"]["collided"] == 0 and link["AUV2"]["collided"] == 0, link

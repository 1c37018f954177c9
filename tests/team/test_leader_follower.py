"""The leader-follower example of docs/missions.md, full stack: the committed
scenario missions/scenarios/leader_follower/ (AUV1 flies two lines, AUV2 keeps
station 30 m astern and 20 m to its left from AUV1's status over the modem),
then the same pair with a leak in the leader mid-line (a planned fault): its
safety rule aborts it, its emergency tells the team, and the follower's plan
catches follow_peer's failure and goes home on its own."""

from __future__ import annotations

import math

import numpy as np
import small_team as st
from conftest import ROOT

SCENARIO = ROOT / "missions" / "scenarios" / "leader_follower" / "leader_follower.yaml"
BEHIND, SIDE = 30.0, -20.0


def station_errors(log):
    """Per shared TRUTH time: the follower's distance from its station on the
    leader's true track (astern by BEHIND, to the right by SIDE)."""
    a = {m.utime: m for _, m in st.messages(log, "AUV1.TRUTH")}
    b = {m.utime: m for _, m in st.messages(log, "AUV2.TRUTH")}
    out = []
    for t in sorted(a.keys() & b.keys()):
        la, fo = a[t], b[t]
        course = la.eta[5]  # the leader's true heading (its course, near enough)
        cn, ce = math.cos(course), math.sin(course)
        sn = la.eta[0] - BEHIND * cn - SIDE * ce
        se = la.eta[1] - BEHIND * ce + SIDE * cn
        out.append((t / 1e6, math.hypot(fo.eta[0] - sn, fo.eta[1] - se)))
    return np.array(out)


def test_the_follower_keeps_station_on_the_leaders_status(tmp_path, lcm_url, child_env):
    # ended after the first line (the time limit: exit 6); the whole scenario to
    # its end is flown by the next test, whose follower goes home
    sc = st.variant(SCENARIO, tmp_path / "lf.yaml", limit_s=200)
    st.fly(sc, tmp_path / "run", lcm_url, child_env, expect_rc=6)
    log = tmp_path / "run" / "run.lcmlog"
    err = station_errors(log)
    # along the first line (after a minute to close up, before its end at 300 m):
    # the station is held from statuses 8.6 s apart, dead-reckoned between
    t = err[:, 0]
    first_line = (t > 90) & (t < 190)
    assert first_line.sum() > 500
    assert np.median(err[first_line, 1]) < 8.0, np.percentile(err[first_line, 1], [50, 90, 100])
    assert np.percentile(err[first_line, 1], 90) < 15.0, np.percentile(err[first_line, 1], [50, 90, 100])
    # the follower never ran into the leader
    a = {m.utime: m.eta for _, m in st.messages(log, "AUV1.TRUTH")}
    b = {m.utime: m.eta for _, m in st.messages(log, "AUV2.TRUTH")}
    gap = [math.hypot(a[k][0] - b[k][0], a[k][1] - b[k][1]) for k in a.keys() & b.keys()]
    assert min(gap) > 10.0, min(gap)


def test_a_leak_aborts_the_leader_and_the_follower_goes_on_alone(tmp_path, lcm_url, child_env):
    """A planned leak (the simulator's leak probes sense water from 60 s on):
    the leader's safety rule aborts it to the surface, its status says abort,
    and the follower, its leader lost, goes home. (A leader lost silently is
    the same failure of follow_peer, after `silent`: tests/team/test_team_faults.py
    covers silence.)"""
    sc = st.variant(SCENARIO, tmp_path / "lf.yaml", faults=[{"at": 60, "vehicle": "AUV1", "do": "leak"}])
    out = st.fly(sc, tmp_path / "run", lcm_url, child_env, expect_rc=3)  # a vehicle aborted
    assert "AUV1: aborted (leak at t=6" in out, out
    assert "AUV2: done" in out and "fault: AUV1 leak at t=60.0 s" in out, out
    log = tmp_path / "run" / "run.lcmlog"
    leak = [(m.utime / 1e6, m.detected) for _, m in st.messages(log, "AUV1.LEAK")]
    assert leak and not any(d for t, d in leak if t < 60.0) and all(d for t, d in leak if t >= 60.0), leak[:70]
    # the leader's emergency told the team (team_safety.chasm): lost at once, not after `silent`
    ev = st.team_events(log)
    lost = [e for e in ev if e[1] == "AUV2" and e[2] == "PEER_LOST" and e[3] == "AUV1"]
    assert lost and "aborted" in lost[0][5] and lost[0][0] < 62.0 + 2 * 8.6 + 5.0, lost
    # follow_peer failed with its leader lost; the plan took the follower home
    states = ["/".join(m.active_path) for _, m in st.messages(log, "AUV2.CHASM.NAVIGATOR") if m.path_len]
    assert any(s.endswith("alone") for s in states), sorted(set(states))
    truth = [m.eta for _, m in st.messages(log, "AUV2.TRUTH")]
    assert min(math.hypot(e[0] + 40, e[1] - 30) for e in truth) < 10.0

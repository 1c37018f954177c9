"""Losing teammates, full stack (issue 15): a small team (2 search vehicles
and a reacquire-identify vehicle) flown by the launcher in lockstep, with
planned faults (docs/scenarios.md, "Faults") that kill every process of a
vehicle mid-mission: the search vehicle AUV2 at 100 s, the RI vehicle AUV3 at
200 s. The survivor must take over and fly AUV2's unflown lines by the rule
every vehicle computes alike, and the contacts nobody can identify any more
must stay in the report as unidentified."""

from __future__ import annotations

import re

import numpy as np
import pytest
import small_team as st
from conftest import child_environment, fresh_url

# a status goes out every 20 s in a TDMA round of 3 x 4.4 s, so a live
# teammate may be unheard for 26 s, longer when a frame is lost: `silent`
# must leave room for that (the planner's default is 120 s)
LOST_SEARCH_AT, LOST_RI_AT, SILENT = 100.0, 200.0, 60.0


@pytest.fixture(scope="module")
def lost_run(tmp_path_factory):
    lcm_url, child_env = fresh_url(), child_environment()
    d = tmp_path_factory.mktemp("team_faults")
    base = st.plan(d / "small")
    silent = {v: {"silent": f"{SILENT:g} s"} for v in ("AUV1", "AUV2", "AUV3")}
    sc = st.variant(
        base,
        d / "lose.yaml",
        params=silent,
        faults=[
            {"at": LOST_SEARCH_AT, "vehicle": "AUV2", "do": "lose"},
            {"at": LOST_RI_AT, "vehicle": "AUV3", "do": "lose"},
        ],
    )
    out = st.fly(sc, d / "run", lcm_url, child_env)
    return d, out, st.report(d / "run", d / "report", child_env)


def test_the_launcher_kills_the_lost_vehicles_and_the_others_finish(lost_run):
    d, out, rep = lost_run
    assert rep["vehicle_outcomes"] == {"AUV1": "done", "AUV2": "lost", "AUV3": "lost"}, rep["vehicle_outcomes"]
    # The world is stepped by the simulators; the launcher takes part in its
    # lockstep (tools/launch/fault_step.py) and kills a vehicle between two steps: it
    # did every step before the planned time and none from it on, however
    # loaded the machine (multi-HIL lockstep step: 0.1 s).
    for vid, at in (("AUV2", LOST_SEARCH_AT), ("AUV3", LOST_RI_AT)):
        hit = re.search(rf"fault: {vid} lost at t=([0-9.]+) s \(planned at {at:g} s[^)]*\): killed (.*)", out)
        assert hit, out
        assert float(hit.group(1)) == at, (vid, hit.group(0))
        assert hit.group(2).split(", ") == [f"{vid}.sim", f"{vid}.PILOT", f"{vid}.NAVIGATOR"], hit.group(2)
        last = max(m.utime for _, m in st.messages(d / "run" / "run.lcmlog", f"{vid}.TRUTH")) / 1e6
        assert at - 0.1 - 1e-6 <= last < at, (vid, last)  # TRUTH at 10 Hz: the step before


def test_the_survivor_takes_over_and_flies_the_lost_vehicles_lines(lost_run):
    d, _, rep = lost_run
    log = d / "run" / "run.lcmlog"
    ev = st.team_events(log)
    lost = [e for e in ev if e[2] == "PEER_LOST" and e[1] == "AUV1" and "AUV2" in e[5] + e[3]]
    assert lost, [e for e in ev if e[2] == "PEER_LOST"]
    # declared lost after the fault, `silent` after the last frame AUV1 heard from it
    heard = [m.utime / 1e6 for _, m in st.messages(log, "AUV1.MODEM_RX") if m.src_vehicle == "AUV2"]
    assert heard and max(heard) <= LOST_SEARCH_AT < lost[0][0], (heard, lost)
    assert SILENT <= lost[0][0] - max(heard) <= SILENT + 0.5, (max(heard), lost)
    assert not [e for e in ev if e[2] == "PEER_LOST" and e[0] < LOST_SEARCH_AT], ev  # nobody else, before
    taken = [e for e in ev if e[2] == "LINES_TAKEN" and e[1] == "AUV1"]
    assert len(taken) == 1 and taken[0][3] == "AUV2", taken
    numbers = [int(x) for x in taken[0][5].split()]
    # AUV2's share is lines 4..7 (plan `lines`); at 100 s it was still on its
    # first: the survivor takes every one it had not finished
    assert set(numbers) <= {4, 5, 6, 7} and {5, 6, 7} <= set(numbers), numbers
    # ... and flies them: the survivor's true track runs along the lines far
    # from its own share (north 0..90 m at east 115.5 and 141.5)
    truth = [(m.utime / 1e6, m.eta[0], m.eta[1]) for _, m in st.messages(log, "AUV1.TRUTH")]
    t, n, e = (np.array(x) for x in zip(*truth))
    for k, east in ((6, 115.5), (7, 141.5)):
        on = (t > taken[0][0]) & (np.abs(e - east) < 4.0) & (n > 10) & (n < 80)
        assert on.sum() >= 0.5 * (70 / 1.5) * 10, (k, int(on.sum()))  # half the 70 m at 10 Hz at least
    # the report lists the takeover
    assert any(
        k["event"] == "LINES_TAKEN" and k["vehicle"] == "AUV1" and k["peer"] == "AUV2" for k in rep["team"]["takeovers"]
    ), rep["team"]["takeovers"]


def test_with_the_ri_vehicle_lost_the_contacts_stay_unidentified(lost_run):
    d, _, rep = lost_run
    ev = st.team_events(d / "run" / "run.lcmlog")
    sent_late = {e[4] for e in ev if e[1] == "AUV1" and e[2] == "CONTACT_SENT" and e[0] > LOST_RI_AT + 5}
    acked_late = {e[4] for e in ev if e[1] == "AUV1" and e[2] == "CONTACT_ACKED" and e[0] > LOST_RI_AT + 5}
    # nothing is acknowledged once the RI vehicle is gone (what the survivor
    # reports from then on, if it finds anything, is repeated in vain)
    assert not acked_late, (sent_late, acked_late)
    # the targets the RI vehicle had queued when it was lost stay unidentified
    queued = {(e[3], e[4]) for e in ev if e[1] == "AUV3" and e[2] == "TARGET_QUEUED" and e[0] < LOST_RI_AT}
    decided = {(e[3], e[4]) for e in ev if e[1] == "AUV3" and e[2] in ("TARGET_IDENTIFIED", "TARGET_NOT_FOUND")}
    assert queued - decided, (queued, decided)
    team = rep["team"]
    unidentified = [
        t
        for t in team["targets"]
        if t["kind"] == "mine_like" and t.get("detected_s") is not None and t.get("identified_s") is None
    ]
    assert unidentified, team["targets"]
    # no identification after the RI vehicle was lost
    assert all(t["identified_s"] is None or t["identified_s"] <= LOST_RI_AT + 0.5 for t in team["targets"])
    assert team["mine_like_identified"] < team["mine_like_detected"], team

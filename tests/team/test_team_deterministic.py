"""The team mission in lockstep runs twice to the same log (issue 14, item 1,
for the demo's kind of world): a small team (2 search vehicles and a
reacquire-identify vehicle, the planner's team plans) stepped by the
simulators' multi-HIL lockstep, talking over the simulated acoustic modem.
Every channel's messages, the modem's included (frames sent, deliveries with
their arrival times and ranges, status counts, the team's events), must be
the same in both runs, in the same order (tests/logcompare.py: what is left
out and why)."""

from __future__ import annotations

import os

import pytest
import small_team as st
from logcompare import SKIP, compare, cut, messages

LIMIT_S = 150.0  # sim time: the first status rounds and contacts
WALL_PACED = ("SIM.CLOCK_SYNC", "SIM.ENV_HEARTBEAT", "SIM.ENV_ELECTION")


# Idle, the two runs are the same (4 of 4, 77 112 messages over 150 s; the old
# modem diverged at 82 s). Under a stress run's load they still diverged in 1 of
# 2 runs (and in 2 of 2 loaded runs with 0.05 s multi-HIL steps, branch
# step-check), first at the RI vehicle's PILOT output
# (AUV3.ACTUATORS at 86.2 s, 123.9 s) while every input recorded for it was
# the same: a race between the managers' cycle and the step's data not found
# yet (issue 14, still open). A test that fails on a busy machine would make
# CI a lottery; it runs when asked: AUV_TEAM_DETERMINISM=1.
@pytest.mark.skipif(
    not os.environ.get("AUV_TEAM_DETERMINISM"),
    reason="team lockstep runs still diverge under load (the RI vehicle's PILOT, issue 14 open); "
    "AUV_TEAM_DETERMINISM=1 runs it",
)
def test_the_team_runs_twice_to_the_same_log(tmp_path, lcm_url, child_env):
    sc = st.variant(st.plan(tmp_path / "small"), tmp_path / "short.yaml", limit_s=LIMIT_S)
    runs = []
    for name in ("a", "b"):
        st.fly(sc, tmp_path / name, lcm_url, child_env, expect_rc=None)
        # the multi-HIL protocol's wall-clock parts: clock sync (wall times),
        # heartbeats and the election (paced by the wall clock)
        runs.append(messages(tmp_path / name / "run.lcmlog", skip=SKIP + WALL_PACED))
    # the world's clock runs on while the launcher stops the vehicles at the limit
    until = min(LIMIT_S * 1e6, *(last for _, last in runs)) - 200_000
    a, b = (cut(per, until) for per, _ in runs)
    assert until >= (LIMIT_S - 5.0) * 1e6, until
    # the modem carried traffic both ways, and the team spoke over it
    for key in ("SIM.ACOUSTIC/AUV1", "SIM.ACOUSTIC/AUV3", "AUV1.MODEM_RX", "AUV3.MODEM_RX", "AUV2.TEAM_EVENT"):
        assert len(a.get(key, [])) >= 3, (key, len(a.get(key, [])))
    compare(a, b)

"""Peer reports end to end over real LCM: AUV2's manager runs the comms
plugin's peer_report behavior, AUV2's simulator sends each new report as a
modem frame, AUV1's simulator hears it after the propagation delay and
publishes AUV1.PEER.AUV2, and AUV1's manager, whose plan binds that channel,
changes state according to where AUV2 is."""

from __future__ import annotations

import subprocess

import pytest
from conftest import ROOT, c_program
from test_modem_lcm import LOSSLESS, world  # noqa: F401  (fixture)

from auv import peer_report_t
from auvlcm import programs

PLANS = ROOT / "tests" / "modem" / "plans"


def manager(world, vehicle: str, plan: str, name: str, sanitized: bool) -> None:
    proc = subprocess.Popen(
        programs.chasm_manager(
            c_program("bin/chasm-manager", sanitized).parents[1],
            plan=PLANS / f"{plan}.chasm",
            bind=PLANS / f"{plan}.bind",
            vehicle=vehicle,
            name=name,
            lcm_url=world.url,
            plugin_path=[c_program("plugins/chasm_comms.so", sanitized).parent],
        ),
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=world.env,
    )
    world.add_manager(vehicle, name, proc)


@pytest.mark.parametrize(
    "sanitized, auv2_north, expected",
    [(False, 300.0, "north_near"), (False, 180.0, "north_close"), (True, -250.0, "south")],
    ids=["normal-300m", "normal-180m", "sanitized-south"],
)
def test_a_plan_reacts_to_another_vehicles_reported_position(
    world,
    sanitized,
    auv2_north,  # noqa: F811
    expected,
):
    world.add_sim("AUV1", 0.0, 0.0, 10.0, LOSSLESS)
    world.add_sim("AUV2", auv2_north, 0.0, 10.0, LOSSLESS)
    manager(world, "AUV2", "reporter", "COMMS", sanitized)
    manager(world, "AUV1", "watcher", "NAVIGATOR", sanitized)
    world.watch("AUV2.PEER_REPORT", peer_report_t)
    world.watch("AUV1.PEER.AUV2", peer_report_t)
    world.wait_for_managers()
    world.run_for(7.0)
    heard = world.msgs["AUV1.PEER.AUV2"]
    # every report published 0.5 s before the end was heard (300 m take 0.2 s)
    published = sorted(
        {r.seq for tick, r in world.arrived_at["AUV2.PEER_REPORT"] if r.seq > 0 and tick <= world.utime - 500_000}
    )
    assert len(published) >= 3  # every 2 s for 7 s
    assert [r.seq for r in heard][: len(published)] == published == list(range(1, len(published) + 1))
    for r in heard:
        assert (r.vehicle, r.heard_by, r.active_state) == ("AUV2", "AUV1", "loitering")
        truth_north = world.truth["AUV2"][r.utime - r.utime % 20_000][0]
        assert abs(r.north_m - truth_north) < 5.0  # the INS's view of the truth
    # each was heard range / c (0.12 to 0.2 s) after the manager's cycle made it; the
    # modem took it at its next step, which may be one step before that cycle's time
    for tick, r in world.arrived_at["AUV1.PEER.AUV2"]:
        assert abs(auv2_north) / 1491 * 1e6 - 20_000 < tick - r.utime < 0.6e6, (r.seq, tick - r.utime)
    status = world.msgs["AUV1.CHASM.NAVIGATOR"]
    leaf = [s.active_path[-1] for s in status if s.active_path]
    # the plan starts when every bound input has delivered, i.e. at the first report
    assert leaf and leaf[-1] == expected, leaf[-5:]
    first_heard = world.arrived_at["AUV1.PEER.AUV2"][0][0]
    assert all(s.utime >= first_heard for s in status if s.active_path and s.active_path[-1] == expected)
    st = world.status("AUV2")
    assert len(heard) <= st.sent <= len(heard) + 1 and st.refused_rate == st.refused_size == st.refused_invalid == 0
    outs = world.close()
    assert f"{len(heard)} peer reports heard" in outs["AUV1"]

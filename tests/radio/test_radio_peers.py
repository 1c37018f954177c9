"""Vehicle to vehicle over the simulated radio (docs/radio.md, "Vehicle to
vehicle"): two vehicles' auv-radio, each on its pty of the radio model, with
--peers: at the surface and in range each publishes the other's status
(<V>.PEER_RADIO_REPORT); once one is out of range, or under water, no more
comes."""

from __future__ import annotations

import signal
import subprocess
import time

import lcm
from conftest import BUILD
from lcm_proc import stop, wait_for_line

from auv import ground_truth_t, nav_solution_t, radio_report_t, sim_clock_t
from auvlcm import programs


def test_teammates_at_the_surface_hear_each_others_status(tmp_path, lcm_url, child_env):
    ptys = {v: tmp_path / f"{v}.radio.pty" for v in ("AUV1", "AUV2")}
    cmds = [programs.radio_sim(vehicles=list(ptys), lcm_url=lcm_url, pipes=ptys, settings={"max_range_m": 1000.0})]
    cmds += [
        programs.radio_vehicle(
            BUILD, vehicle=v, spool=tmp_path / v, lcm_url=lcm_url, port=ptys[v], report_period_s=0.2, peers=[o]
        )
        for v, o in (("AUV1", "AUV2"), ("AUV2", "AUV1"))
    ]
    procs = [subprocess.Popen(cmds[0], env=child_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)]
    wait_for_line(procs[0], ": ready", timeout=30)  # its ptys are made: the gateways open them at once
    procs += [
        subprocess.Popen(c, env=child_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for c in cmds[1:]
    ]
    for p in procs[1:]:
        wait_for_line(p, ": ready", timeout=30)
    lc = lcm.LCM(lcm_url)
    heard: list[tuple[str, radio_report_t, int]] = []
    utime = 1_000_000
    lc.subscribe(r"AUV\d\.PEER_RADIO_REPORT", lambda c, d: heard.append((c, radio_report_t.decode(d), utime)))

    def sail(seconds: float, north2: float, depth2: float, until=lambda: False) -> bool:
        nonlocal utime
        end = utime + int(seconds * 1e6)
        while utime < end and not until():
            utime += 50_000
            for v, north, depth in (("AUV1", 0.0, 0.0), ("AUV2", north2, depth2)):
                t = ground_truth_t()
                t.utime, t.vehicle, t.eta = utime, v, [north, 0.0, depth, 0.0, 0.0, 0.0]
                lc.publish(f"{v}.TRUTH", t.encode())
                nav = nav_solution_t()
                nav.utime, nav.vehicle, nav.depth_m, nav.north_m = utime, v, depth, north
                lc.publish(f"{v}.NAV", nav.encode())
            clock = sim_clock_t()
            clock.utime, clock.server_id, clock.step_us = utime, "test", 50_000
            lc.publish("SIM.CLOCK", clock.encode())
            pace = time.monotonic() + 0.01
            while time.monotonic() < pace:
                lc.handle_timeout(1)
        return until()

    try:
        chans = lambda: {c for c, _, _ in heard}  # noqa: E731
        assert sail(20.0, 300.0, 0.0, lambda: len(chans()) == 2), heard
        at = utime
        sail(2.0, 3000.0, 0.0)  # AUV2 sails out of range ...
        sail(2.0, 300.0, 5.0)  # ... then dives back in range: under water
    finally:
        codes = [stop(p, signal.SIGTERM) for p in procs]
        errs = [p.stderr.read() for p in procs]
    assert codes == [0, 0, 0], errs
    assert {(c, m.vehicle) for c, m, _ in heard} == {
        ("AUV1.PEER_RADIO_REPORT", "AUV2"),
        ("AUV2.PEER_RADIO_REPORT", "AUV1"),
    }
    late = [u for _, _, u in heard if u > at + 500_000]  # the air and the pace: half a second's grace
    assert not late, (late, at)
    assert "peer reports 0" not in errs[1] and "peer reports 0" not in errs[2], errs

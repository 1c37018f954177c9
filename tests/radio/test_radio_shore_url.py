"""The shore on an LCM of its own (docs/radio.md, "Two worlds"): the radio model
bridges the shore's LCM and the vehicles' (auv-radio-sim --shore-lcm-url), the
shore gateway runs on the shore's, the vehicle's auv-radio on the vehicles'
(on the model's pty). A command published on the shore's LCM reaches the
vehicle's byte for byte and the status comes home; nothing of one world
appears on the other but the world's clock, copied to the shore."""

from __future__ import annotations

import signal
import subprocess
import time

import lcm
from conftest import BUILD, fresh_url
from lcm_proc import stop, wait_for_line

from auv import ground_truth_t, mission_command_t, nav_solution_t, sim_clock_t
from auvlcm import programs


def test_the_shore_on_its_own_lcm_reaches_the_vehicle_through_the_radio(tmp_path, lcm_url, child_env):
    shore_url = fresh_url()
    pty = tmp_path / "AUV1.radio.pty"
    cmds = [
        programs.radio_sim(
            vehicles=["AUV1"], lcm_url=lcm_url, pipes={"AUV1": pty}, shore_lcm_url=shore_url, settings={"seed": 1}
        ),
        programs.radio_shore(vehicles=["AUV1"], lcm_url=shore_url, link_timeout_s=1.0, retry_s=1.0),
        programs.radio_vehicle(BUILD, vehicle="AUV1", spool=tmp_path / "spool", lcm_url=lcm_url, port=pty)
        + ["--report-period-s", "0.3"],
    ]
    procs = [
        subprocess.Popen(c, env=child_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for c in cmds
    ]
    for p in procs:
        wait_for_line(p, ": ready", timeout=30)
    sea, shore = lcm.LCM(lcm_url), lcm.LCM(shore_url)
    on_sea: list[tuple[str, bytes]] = []
    on_shore: list[tuple[str, bytes]] = []
    sea.subscribe(".*", lambda c, d: on_sea.append((c, d)))
    shore.subscribe(".*", lambda c, d: on_shore.append((c, d)))
    cmd = mission_command_t()
    cmd.vehicle, cmd.seq, cmd.command, cmd.reason = "AUV1", 5, mission_command_t.CMD_PAUSE, "shore url test"
    data = cmd.encode() + b"SIGNED"
    utime, sent = 1_000_000, False
    try:
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and ("AUV1.MISSION_CMD", data) not in on_sea:
            utime += 50_000
            truth = ground_truth_t()
            truth.utime, truth.vehicle, truth.eta = utime, "AUV1", [100.0, 0.0, 0.0, 0.0, 0.0, 0.0]
            sea.publish("AUV1.TRUTH", truth.encode())
            nav = nav_solution_t()
            nav.utime, nav.vehicle, nav.depth_m = utime, "AUV1", 0.0
            sea.publish("AUV1.NAV", nav.encode())
            clock = sim_clock_t()
            clock.utime, clock.server_id, clock.step_us = utime, "test", 50_000
            sea.publish("SIM.CLOCK", clock.encode())
            if not sent and any(c == "SHORE.AUV1.RADIO_REPORT" for c, _ in on_shore):
                shore.publish("SHORE.AUV1.MISSION_CMD", data)  # the operator's, on the shore's network
                sent = True
            pace = time.monotonic() + 0.01
            while time.monotonic() < pace:
                sea.handle_timeout(1)
                shore.handle_timeout(1)
    finally:
        codes = [stop(p, signal.SIGTERM) for p in procs]
        errs = [p.stderr.read() for p in procs]
    assert codes == [0, 0, 0], errs
    assert sent and ("AUV1.MISSION_CMD", data) in on_sea, (sorted({c for c, _ in on_sea}), errs)
    sea_channels, shore_channels = {c for c, _ in on_sea}, {c for c, _ in on_shore}
    assert not {c for c in sea_channels if c.startswith("SHORE.") or c.endswith(".SHORE")}, sea_channels
    assert shore_channels <= {
        "SIM.CLOCK",
        "RADIO.TX.SHORE",
        "RADIO.RX.SHORE",
        "SHORE.AUV1.MISSION_CMD",
        "SHORE.AUV1.RADIO_REPORT",
        "SHORE.AUV1.RADIO_CMD_STATUS",
        "SHORE.AUV1.MISSION_ACK",
    }, shore_channels
    assert "RADIO.RX.SHORE" in shore_channels and "RADIO.RX.SHORE" not in sea_channels

"""The sonar in the simulator process over real LCM: SIM.TARGETS and <V>.CONTACTS.

The test is the global clock (stepped mode) and flies the vehicle north with
a scripted autopilot, answering each step's NAV before the next, past a
target file: exact under any CPU load."""

from __future__ import annotations

import math
from pathlib import Path

import lcm
from lcm_proc import start_simulator, stop
from lockstep import LockstepPilot
from test_hil_lcm import Recorder

from auv import sidescan_contact_t, target_field_t

ROOT = Path(__file__).resolve().parents[2]

CONFIG = """
vehicle: {{id: AUV2}}
simulation: {{clock: lockstep, lcm_url: "{url}"}}
initial: {{depth_m: 5.0, speed_mps: 1.5, prop_rpm: 1500}}
environment: {{seed: 5, bathymetry: "flat:depth=15"}}
sensors: {{ins: {{rate_hz: 25, bias: 0.0}}, depth: {{}}}}
sonar:
  false_alarms_per_km2: 0
  publish_targets: yes
  targets: {{file: targets.csv}}
"""
TARGETS = [
    (1, 20.0, 15.0),
    (2, 25.0, -15.0),
    (3, 30.0, 25.0),
    (4, 35.0, -25.0),
    (5, 40.0, 20.0),
    (6, 45.0, -20.0),
    (7, 50.0, 30.0),
    (8, 55.0, -30.0),
]


def test_contacts_and_target_field_over_lcm(tmp_path, child_env, lcm_url):
    (tmp_path / "targets.csv").write_text(
        "id,north_m,east_m,kind,length_m\n" + "".join(f"{i},{n},{e},mine_like,1.5\n" for i, n, e in TARGETS)
    )
    cfg = tmp_path / "sim.yaml"
    cfg.write_text(CONFIG.format(url=lcm_url))
    lc = lcm.LCM(lcm_url)
    rec = Recorder(lc)
    rec.sub("AUV2.CONTACTS", sidescan_contact_t)
    rec.sub("SIM.TARGETS", target_field_t)
    pilot = LockstepPilot(lc, "AUV2", depth_m=5.0)
    proc = start_simulator(cfg, child_env)
    try:
        pilot.fly(45.0)  # past the last target at 55 m north
        lc.handle_timeout(100)
    finally:
        assert stop(proc) == 0
    fields = rec.msgs["SIM.TARGETS"]
    assert len(fields) == 5  # at 0 s, then every 10 s of sim time
    assert fields[0].n_targets == 8 and fields[0].source.endswith("targets.csv")
    assert fields[0].targets[0].depth_m == 15.0
    contacts = rec.msgs["AUV2.CONTACTS"]
    assert 5 <= len(contacts) <= 8  # P = 0.9 each at 10 m altitude
    assert [c.contact_id for c in contacts] == list(range(1, len(contacts) + 1))
    for c in contacts:
        near = min(TARGETS, key=lambda t: math.hypot(c.north_m - t[1], c.east_m - t[2]))
        assert math.hypot(c.north_m - near[1], c.east_m - near[2]) < 4.0
        assert c.vehicle == "AUV2" and c.side == (1 if near[2] > 0 else 0)
        assert abs(c.utime / 1e6 - near[1] / 1.5) < 8.0  # when it passed abeam
        assert 9.0 < c.vehicle_altitude_m < 11.0

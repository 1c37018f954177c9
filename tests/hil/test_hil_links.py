"""auv-hil-wire's plan of the links (python/tools/hil/links.py, cli.prepare): the
ports, the simulator's wired configuration (every device's `wire:` accepted by the
simulator's own checks), each driver's port and flags; a bad scenario is refused."""

from __future__ import annotations

import json
import subprocess
import sys
from argparse import Namespace
from pathlib import Path

from conftest import ROOT

from sim.config import load
from tools.hil.cli import prepare
from tools.hil.links import PORTS_PER_VEHICLE, plan_links
from tools.scenario.scenario_file import load_scenario

TEAM = ROOT / "missions" / "scenarios" / "mcm_team" / "mcm_team.yaml"


def test_each_vehicle_gets_its_block_of_ports():
    devices = ["timesync", "gps", "dvl", "servo"]
    a, b = plan_links(devices, 0, 4100, None), plan_links(devices, 2, 4100, None)
    assert [x.tcp_port for x in a] == [4100, 4101, 4102, 4103]
    assert [x.tcp_port for x in b] == [4100 + 2 * PORTS_PER_VEHICLE + k for k in range(4)]
    assert a[0].driver_port("10.0.0.5") == {"tcp": "10.0.0.5:4100"}
    pty = plan_links(["gps"], 0, 4100, Path("/tmp/x"))[0]
    assert pty.sim_wire() == {"protocol": "nmea", "pty": "/tmp/x/gps", "baud": 9600, "publish_lcm": False}


def test_the_team_wired(tmp_path):
    sc = load_scenario(TEAM)
    args = Namespace(out=tmp_path, transport="tcp", base_port=4100, sim_host="10.1.2.3", warp=4.0)
    plan = prepare(sc, args)
    assert set(plan) == {"AUV1", "AUV2", "AUV3", "AUV4"}
    ports = set()
    for i, (vid, files) in enumerate(plan.items()):
        cfg = load(files["sim"])  # the simulator's own checks accept every wire
        assert cfg.multihil.enabled and cfg.sim.clock == "scaled" and cfg.sim.warp == 4.0
        assert cfg.time_link.rate_hz == 50 and cfg.actuators.wire.protocol == "maestro"
        assert not cfg.sensors["gps"].wire.publish_lcm and cfg.modem.wire.options.table == "AUV1=1,AUV2=2,AUV3=3,AUV4=4"
        links = json.loads(files["links"].read_text())
        ri = vid == "AUV4"  # the reacquire-identify vehicle: looks, no sonar
        want = {"timesync", "gps", "ahrs", "depth", "dvl", "servo", "modem", "payload_looks" if ri else "payload"}
        assert set(links["drivers"]) == want
        assert all(d["tcp"].startswith("10.1.2.3:41") for d in links["drivers"].values())
        ports |= {d["tcp"] for d in links["drivers"].values()}
        assert links["flags"]["modem"] == ["--table", "AUV1=1,AUV2=2,AUV3=3,AUV4=4"]
        assert links["flags"]["gps"][0] == "--origin"
        assert files["nav"].read_text().startswith("#") or "origin_latitude_deg" in files["nav"].read_text()
    assert len(ports) == 4 * 8  # no port twice


def test_a_bad_scenario_is_refused_with_its_place(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\n")
    run = subprocess.run(
        [sys.executable, "-m", "tools.hil.cli", str(bad), "--out", str(tmp_path / "o")], capture_output=True, text=True
    )
    assert run.returncode == 2
    assert f"{bad}:1:1: bad.yaml: missing required key 'vehicles'" in run.stderr

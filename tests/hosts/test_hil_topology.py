"""The seed's HIL topology on network namespaces (docs/multihil.md, "HIL
topology"): four vehicle computers (each its vehicle's PILOT and NAVIGATOR),
two simulator PCs (AUV1's simulator, which serves the world; the others'),
one operator (lcm-logger and a watcher). The cooperative MCM team
(missions/scenarios/mcm_team: three search vehicles and a reacquire-identify
vehicle on one acoustic link), its vehicles' multi-HIL simulators keeping the
time, flies across them; then the simulator PC that serves the world dies, and
later AUV3's vehicle computer: the world fails over to AUV2's simulator and
keeps one clock; AUV1, its simulation gone, aborts on stale navigation and its
emergency tells the team; AUV3 falls silent; AUV2 flies on and takes over both
teammates' lines, AUV3's simulator goes on simulating a vehicle whose software
is gone, and AUV1's simulation ends with its PC.

Command lines come from the host agents' part builder (tools/hosts/agent_part.py),
so each process is exactly what an agent or the launcher would run; the test
places them itself because an agent runs a whole vehicle on one host.
Needs network namespaces (tests/isolated_net.sh, as `make test` runs it).
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys

import pytest
import yaml
from agents import wait_until
from conftest import ROOT
from netns import Hosts, hosts_or_skip

from tools.hosts.agent_part import host_part

URL = "udpm://239.255.76.67:7667?ttl=1"
MCM = ROOT / "missions" / "scenarios" / "mcm_team" / "mcm_team.yaml"
WARP = 4.0
VC = {"AUV1": 1, "AUV2": 2, "AUV3": 3, "AUV4": 4}  # vehicle computers
SIM_PC = {"AUV1": 5, "AUV2": 6, "AUV3": 6, "AUV4": 6}  # simulator PCs: 5 serves the world (best priority)
OPERATOR = 7
PRIORITY = {"AUV1": 30, "AUV2": 20, "AUV3": 10, "AUV4": 5}
# A silent teammate is lost after this (the plans' default is 120 s): longer
# than a status period (20 s) and a TDMA round (4 x 4.4 s) together.
SILENT_S = 45.0


@pytest.fixture
def hosts():
    h = hosts_or_skip(7, 79, "the HIL topology")
    yield h
    h.close()


def hil_scenario() -> str:
    """The MCM team with a vehicle computer per vehicle and the time on its simulators."""
    doc = yaml.safe_load(MCM.read_text())
    doc["hosts"] = [f"vc{i}" for i in VC.values()]
    doc["time"] = {"source": "simulators", "limit": 3600}
    for v in doc["vehicles"]:
        v["host"] = f"vc{VC[v['id']]}"
        v["sim"]["simulation"] = {"clock": "scaled", "warp": WARP}
        v["sim"]["multihil"] = {"enabled": True, "priority": PRIORITY[v["id"]]}
        for m in v["managers"]:
            if m["name"] == "NAVIGATOR":
                m["params"] = {"silent": f"{SILENT_S:g} s"}
    return yaml.safe_dump(doc, sort_keys=False)


class Procs:
    def __init__(self, hosts: Hosts, env: dict) -> None:
        self.hosts, self.env, self.procs = hosts, env, {}

    def start(self, name: str, cmd: list, out, host: int) -> None:
        self.procs[name] = (
            subprocess.Popen(
                [*self.hosts.prefix(host), *map(str, cmd)],
                stdout=open(out, "w"),
                stderr=subprocess.STDOUT,
                env=self.env,
                start_new_session=True,
            ),
            host,
        )

    def kill_host(self, host: int) -> list[str]:
        """Everything on one machine dies at once (power cut)."""
        gone = [n for n, (_, h) in self.procs.items() if h == host]
        for n in gone:
            p = self.procs[n][0]
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
        return gone

    def stop(self) -> None:
        for n, (p, _) in self.procs.items():
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGINT)
        for n, (p, _) in self.procs.items():
            try:
                p.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()


def test_hil_topology_survives_a_simulator_pc_and_a_vehicle_computer(hosts, tmp_path, child_env, build_dir):
    env = Hosts.env(child_env)
    text = hil_scenario()
    procs = Procs(hosts, env)
    observer = tmp_path / "operator.jsonl"
    try:
        parts = {
            vid: host_part(text, str(MCM), f"vc{i}", tmp_path / f"vc{i}", URL, build_dir, True)[1]
            for vid, i in VC.items()
        }
        procs.start("observer", [sys.executable, ROOT / "tests" / "hosts" / "observe.py", URL, *VC], observer, OPERATOR)
        for vid, specs in parts.items():
            for s in specs:
                if s.name == "logger":
                    procs.start(s.name, s.cmd, s.out, OPERATOR)
                elif not s.name.endswith(".sim"):
                    procs.start(s.name, s.cmd, s.out, VC[vid])
        for vid, specs in parts.items():  # AUV1's first: it serves the world
            sim = next(s for s in specs if s.name.endswith(".sim"))
            procs.start(sim.name, sim.cmd, sim.out, SIM_PC[vid])
            if vid == "AUV1":
                wait_until(lambda: "server for term 1" in sim.out.read_text(), 60, "AUV1-sim serves", step=0.2)

        def view() -> dict:
            for line in reversed(observer.read_text().splitlines()[-2:]):
                try:
                    return json.loads(line)
                except ValueError:  # the line being written
                    continue
            return {"servers": [], "clock_s": 0, "nav": {}, "truth": {}, "lost": [], "taken": []}

        def flying(v, vids) -> bool:
            return all(v["nav"].get(x, [0])[0] == 1 for x in vids)

        v0 = wait_until(lambda: (v := view()) and flying(v, VC) and v["clock_s"] > 6 and v, 60, "all three flying")
        assert v0["servers"] == ["AUV1-sim"], v0
        procs.kill_host(SIM_PC["AUV1"])  # the simulator PC that serves the world
        t_pc = view()["clock_s"]
        v1 = wait_until(lambda: (v := view())["clock_s"] > t_pc + 8 and v, 60, "the world goes on")
        assert v1["servers"] == ["AUV1-sim", "AUV2-sim"], v1
        procs.kill_host(VC["AUV3"])  # a vehicle computer
        t_vc = view()["clock_s"]

        def carried_on(v) -> bool:
            # every teammate that declares AUV3 lost must have done so (each `silent`
            # after it last heard AUV3: AUV4 may have heard it a TDMA round later)
            declared = {x[1] for x in v["lost"] if x[2] == "AUV3"}
            return v["clock_s"] > t_vc + 8 and declared >= {"AUV2", "AUV4"} and any(x[2] == "AUV3" for x in v["taken"])

        end = wait_until(
            lambda: (v := view()) and carried_on(v) and v, 120, "AUV3 lost by AUV2 and AUV4 and its lines taken"
        )
    finally:
        procs.stop()
    # the world failed over once, to the next priority, and kept one clock
    assert end["servers"] == ["AUV1-sim", "AUV2-sim"], end
    # AUV2 flies on through both losses: still running its plan, moving, on the current time
    run, path, t_status = end["nav"]["AUV2"]
    assert run == 1 and t_status > t_vc + 6, end
    moved = math.dist(v1["truth"]["AUV2"][1:], end["truth"]["AUV2"][1:])
    assert moved > 0.5 * (end["clock_s"] - v1["clock_s"]), (v1, end)  # > 0.5 m/s
    # AUV3's teammates carry on: each declared it lost, `silent` after they last heard it,
    # and the search vehicles still flying took its lines by the shared rule
    lost = [x for x in end["lost"] if x[2] == "AUV3"]
    assert {x[1] for x in lost} >= {"AUV2", "AUV4"}, end["lost"]
    assert all(t_vc < x[0] <= t_vc + SILENT_S + 2.0 for x in lost), (t_vc, lost)
    taken = [x for x in end["taken"] if x[2] == "AUV3"]
    assert taken and {x[1] for x in taken} <= {"AUV1", "AUV2"}, end["taken"]
    # AUV3: its software went with its computer, its simulator did not
    assert end["nav"]["AUV3"][2] < t_vc + 2.0 and end["truth"]["AUV3"][0] > t_vc + 6, end
    # AUV1: its simulation ended with its PC
    assert end["truth"]["AUV1"][0] < t_pc + 2.0, end

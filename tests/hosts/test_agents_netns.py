"""Host agents on two machines: network namespaces on a bridge, LCM ttl=1
between them, agentctl on a third. The scenario keeps time on its simulators
(multi-HIL), so once the agents have their parts the mission flies with no
launcher at all: both vehicles finish, on one world clock; then one stop
ends both parts and nothing is left.

Needs network namespaces (tests/isolated_net.sh, as `make test` runs it).
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from agents import AGENTCTL, AgentProc, alive, vehicle, wait_until, write_scenario
from conftest import ROOT
from netns import Hosts, hosts_or_skip

URL = "udpm://239.255.76.67:7667?ttl=1"


@pytest.fixture
def hosts():
    h = hosts_or_skip(3, 78, "host agents across namespaces")
    yield h
    h.close()


def ctl(hosts, env, *args, timeout=90):
    return subprocess.run(
        [*hosts.prefix(3), *AGENTCTL, *args, "--lcm-url", URL, "--netns"],
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def test_agents_on_two_machines_fly_a_mission_without_a_launcher(hosts, tmp_path, child_env):
    env = Hosts.env(child_env)
    agents = [
        AgentProc(h, URL, tmp_path / "agents", env, prefix=hosts.prefix(i), extra=("--netns",))
        for i, h in ((1, "alpha"), (2, "beta"))
    ]
    try:

        def mh(priority):
            return {"simulation": {"clock": "scaled", "warp": 2.0}, "multihil": {"enabled": True, "priority": priority}}

        v1, v2 = vehicle("AUV1", "alpha", cycles=30), vehicle("AUV2", "beta", east=40, cycles=40)
        v1["sim"].update(mh(20))
        v2["sim"].update(mh(10))
        sc = write_scenario(
            tmp_path / "hil.yaml", [v1, v2], ["alpha", "beta"], time={"source": "simulators", "limit": 60}
        )
        wait_until(
            lambda: ctl(hosts, env, "status", "--host", "alpha", "--host", "beta", "--timeout", "3").returncode == 0,
            60,
            "both agents heard from the third machine",
            step=0.5,
        )
        watch = subprocess.Popen(
            [
                *hosts.prefix(3),
                sys.executable,
                str(ROOT / "tests" / "hosts" / "watch_done.py"),
                URL,
                "60",
                "AUV1",
                "AUV2",
            ],
            env=env,
            stdout=subprocess.PIPE,
            text=True,
        )
        run = ctl(hosts, env, "start", str(sc), "--restart", "*=never")
        assert run.returncode == 0, run.stdout + run.stderr
        out = watch.communicate(timeout=90)[0]
        assert watch.returncode == 0, out + "".join(a.text() for a in agents)
        # One world clock for the whole run. Which simulator serves it is not the
        # test's to say: each agent starts its own, and a free-running world is
        # served by the first to stand, whatever its priority (docs/multihil.md);
        # under load beta's started more than a join window before alpha's.
        servers = out.strip().rsplit("clock from ", 1)[1].split()
        assert len(servers) == 1 and servers[0] in ("AUV1-sim", "AUV2-sim"), out
        status = ctl(hosts, env, "status", "--host", "alpha", "--host", "beta", "--json")
        tables = {t["host"]: t for t in json.loads(status.stdout)}
        assert {p["name"]: p["state"] for p in tables["beta"]["procs"]} == {
            "AUV2.sim": "running",
            "AUV2.NAVIGATOR": "running",
            "AUV2.WATCHER": "running",
        }
        pids = [p["pid"] for t in tables.values() for p in t["procs"]]
        assert all(p["rss_bytes"] > 0 for t in tables.values() for p in t["procs"])
        stop = ctl(hosts, env, "stop", str(sc))
        assert stop.returncode == 0, stop.stdout + stop.stderr
        assert "alpha: ok: stopped 4 process(es)" in stop.stdout and "beta: ok: stopped 3" in stop.stdout
        assert not any(alive(p) for p in pids)
        assert (tmp_path / "agents" / "alpha" / "hil" / "run.lcmlog").stat().st_size > 10000
    finally:
        for a in agents:
            a.stop()

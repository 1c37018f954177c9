"""Three hosts (network namespaces on a bridge, LCM ttl=1 between them), each
a simulator and its navigator manager, one world. The server's simulator is
SIGKILLed mid-mission: another host takes over, the global time stays
monotonic and without a jump, and every surviving vehicle finishes its plan.

Needs network namespaces: `make test` runs inside tests/isolated_net.sh, where
it can build them. Alone: tests/isolated_net.sh .venv/bin/python -m pytest
tests/multihil/test_multihost.py
"""

from __future__ import annotations

import time

import pytest
from netns import Hosts, hosts_or_skip

from auvlcm.log import read_events
from tools.launch.world import VehicleSpec, World

# Free-running at 2x: a starved process (a loaded CI machine) lags the global
# clock by wall time x warp, and the plan aborts on navigation older than 5 s.
WARP = 2.0
MISSION_S = 20.0  # the depth-band plan's time in the band before it surfaces


@pytest.fixture
def hosts():
    h = hosts_or_skip(4, 77, "the multi-host test")
    yield h
    h.close()


def navigator_states(log, until_wall_us: float) -> tuple[dict, list, list]:
    """Navigator state changes, clock and heartbeats, before the test began stopping."""
    states: dict[str, list[tuple[int, str, str]]] = {}
    clock, servers = [], []
    for ev in read_events(log):
        m = ev.msg
        if m is None or ev.timestamp > until_wall_us:
            continue
        if ev.channel.endswith(".CHASM.NAVIGATOR") and m.path_len:
            path = "/".join(m.active_path)
            seq = states.setdefault(m.vehicle, [])
            if not seq or seq[-1][1] != path:
                seq.append((m.utime, path, m.last_condition))
        elif ev.channel == "SIM.CLOCK":
            clock.append((ev.timestamp, m.utime, m.server_id, m.term))
        elif ev.channel == "SIM.ENV_HEARTBEAT":
            servers.append((m.server_id, m.term))
    return states, clock, servers


def test_three_hosts_survive_the_loss_of_the_server(hosts, tmp_path, child_env, build_dir):
    url = "udpm://239.255.76.67:7667?ttl=1"
    world = World(tmp_path, url, build_dir, Hosts.env(child_env))
    log = tmp_path / "world.lcmlog"
    world.logger(log, hosts.prefix(4))
    specs = [VehicleSpec(f"AUV{i}", priority=40 - 10 * i, east_m=25.0 * i) for i in (1, 2, 3)]
    try:
        for i, s in enumerate(specs, 1):
            # a mission of its own: each vehicle keeps to a different depth band
            world.managers(
                s,
                hosts.prefix(i),
                extra=["-D", f"duration={MISSION_S:g} s", "-D", f"low={1 + 2 * i} m", "-D", f"high={3 + 2 * i} m"],
            )
            world.simulator(s, "scaled", {}, warp=WARP, prefix=hosts.prefix(i))
        out1 = tmp_path / "AUV1.sim.out"
        deadline = time.monotonic() + 60
        while "server for term 1" not in out1.read_text() and time.monotonic() < deadline:
            time.sleep(0.1)
        assert "server for term 1" in out1.read_text(), out1.read_text()
        time.sleep(8.0 / WARP + 1.0)  # well into the mission
        world.kill("AUV1.sim")
        time.sleep(MISSION_S / WARP + 3.0)  # past the end of the mission
    finally:
        stopping = time.time() * 1e6  # lcm-logger stamps with the wall clock
        world.stop()
    states, clock, servers = navigator_states(log, stopping)
    assert clock, world.output("logger")
    # a new server took over: the next by priority, in a higher term
    assert [s for s in dict.fromkeys(servers)] == [("AUV1-sim", 1), ("AUV2-sim", 2)], servers
    # monotonic global time, and no jump across the failover beyond the clock period
    assert all(b[1] >= a[1] for a, b in zip(clock, clock[1:]))
    last1 = [c for c in clock if c[2] == "AUV1-sim"][-1]
    first2 = [c for c in clock if c[2] == "AUV2-sim"][0]
    expected = last1[1] + (first2[0] - last1[0]) * WARP
    assert abs(first2[1] - expected) < 0.3e6, (last1, first2)
    # the survivors flew their plan to its end, on the global clock
    for v in ("AUV2", "AUV3"):
        seq = states[v]
        assert seq[-1][1] == "surface" and seq[-1][2] == "elapsed > $duration", (v, seq)
        assert abs(seq[-1][0] / 1e6 - (seq[0][0] / 1e6 + MISSION_S)) < 1.0, seq
        assert any(p.startswith("transit/") for _, p, _ in seq)
    assert "server for term 2" in world.output("AUV2.sim")

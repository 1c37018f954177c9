"""Two sites joined only through Zenoh (docs/zenoh.md): each site a network
namespace whose LCM (ttl=0) is its own multicast domain, a Zenoh router on a
third machine, a bridge at each site in client mode (the router is the only
way between them). A two-vehicle multi-HIL world split
between the sites keeps one environment and one clock: the remote simulator
is a client of the local one's server and adopts its world; both navigators
fly on the one global time; nothing loops (no message arrives twice).

Needs network namespaces (tests/isolated_net.sh, as `make test` runs it) and
the eclipse-zenoh package (requirements.txt).
"""

from __future__ import annotations

import os
import re
import sys
import time

import pytest
from agents import wait_until
from netns import Hosts, hosts_or_skip

from tools.launch.world import VehicleSpec, World

BRIDGE = [sys.executable, "-m", "tools.bridges.zenoh_bridge"]
SITE_URL = "udpm://239.255.76.67:7667?ttl=0"  # never leaves its site's machine
WARP = 2.0


@pytest.fixture
def hosts():
    pytest.importorskip("zenoh", reason="the eclipse-zenoh package is not installed (requirements.txt)")
    h = hosts_or_skip(3, 80, "Zenoh sites")
    yield h
    h.close()


def addr(hosts: Hosts, i: int) -> str:
    return f"10.80.{os.getpid() % 1000 % 250}.{i}"


def test_two_sites_share_one_world_and_one_clock_through_zenoh(hosts, tmp_path, child_env, build_dir):
    env = Hosts.env(child_env)
    router_ep = f"tcp/{addr(hosts, 3)}:7447"
    world_a = World(tmp_path / "siteA", SITE_URL, build_dir, env)
    world_b = World(tmp_path / "siteB", SITE_URL, build_dir, env)
    side = World(tmp_path / "net", SITE_URL, build_dir, env)  # the router and the bridges
    try:
        side._start("router", [*BRIDGE, "router", "--listen", router_ep], hosts.prefix(3))
        wait_until(lambda: "router on" in side.output("router"), 60, "the router listens", step=0.1)
        for i, site in ((1, "shipA"), (2, "labB")):
            side._start(
                f"bridge.{site}",
                [
                    *BRIDGE,
                    "--site",
                    site,
                    "--realm",
                    "test",
                    "--lcm-url",
                    SITE_URL,
                    "--connect",
                    router_ep,
                    "--mode",
                    "client",
                    "--deny",
                    r".*\.TRUTH",
                    "--stats-period",
                    "1",
                ],
                hosts.prefix(i),
            )
        log_b = tmp_path / "siteB.lcmlog"
        world_b.logger(log_b, hosts.prefix(2))
        a, b = VehicleSpec("AUV1", priority=20), VehicleSpec("AUV2", priority=10, east_m=30.0)
        world_a.managers(a, hosts.prefix(1), extra=["-D", "duration=10 s"])
        world_b.managers(b, hosts.prefix(2), extra=["-D", "duration=10 s"])
        world_a.simulator(a, "scaled", {}, warp=WARP, prefix=hosts.prefix(1))
        wait_until(lambda: "server for term 1" in world_a.output("AUV1.sim"), 60, "site A serves", step=0.2)
        world_b.simulator(b, "scaled", {}, warp=WARP, prefix=hosts.prefix(2))
        wait_until(
            lambda: "client of AUV1-sim (term 1)" in world_b.output("AUV2.sim"),
            60,
            "site B's simulator joins site A's world",
            step=0.2,
        )
        time.sleep(8.0 / WARP)  # some flight on the shared clock
        stopping = time.time() * 1e6
    finally:
        world_a.stop()
        world_b.stop()
        side.stop()
    out_b = world_b.output("AUV2.sim")
    assert "server for term" not in out_b, out_b  # one server for both sites: one clock
    assert re.search(r"0 mismatches", out_b), out_b  # one environment: the samples agree with its own
    from auvlcm.log import read_events

    clock, status_b, truth_a, seen = [], 0, 0, {}
    dups = 0
    for ev in read_events(log_b):
        if ev.msg is None or ev.timestamp > stopping:
            continue
        key = (ev.channel, ev.msg.encode())
        dups += key in seen and ev.channel in ("SIM.CLOCK", "AUV1.NAV")
        seen[key] = True
        if ev.channel == "SIM.CLOCK":
            clock.append((ev.msg.server_id, ev.msg.utime))
        status_b += ev.channel == "AUV2.CHASM.NAVIGATOR"
        truth_a += ev.channel == "AUV1.TRUTH"
    assert clock and {s for s, _ in clock} == {"AUV1-sim"}  # site B runs on site A's clock
    assert all(y >= x for (_, x), (_, y) in zip(clock, clock[1:]))
    assert status_b > 20 and truth_a == 0  # the deny rule held
    assert dups == 0  # no loop, no echo
    stats = side.output("bridge.labB")
    assert re.search(r"received [1-9]", stats) and re.search(r"sent [1-9]", stats), stats
    assert re.search(r"echoes [1-9]", stats), stats  # its own injections heard back, not resent

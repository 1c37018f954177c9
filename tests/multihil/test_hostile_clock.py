"""Multi-HIL nodes and simulators against hostile SIM.CLOCK traffic (issue 12,
items 3 and 6), as processes over real LCM.

- Stamps at 10^18, a valid but far-future stamp (a jump), an older term: a
  client drops each and counts it; when the server then dies, the client
  takes over from the last clock it accepted, so the world's time goes on
  from where it was instead of from 10^18 or 2096.
- Garbage on every world channel of a multi-HIL simulator is counted in its
  HEALTH (the node's subscriptions included), and the simulator runs on.
"""

from __future__ import annotations

import re

import lcm
from lcm_proc import pump
from mh_util import (
    Listener,
    Proc,
    node_cmd,
    procs,  # noqa: F401 (a fixture)
    sim_cmd,
    vehicle_config,
)

from auv import process_health_t, sim_clock_t


def clock(utime: int, term: int, server: str = "S-sim") -> bytes:
    c = sim_clock_t()
    c.utime, c.server_id, c.term, c.mode, c.warp = utime, server, term, sim_clock_t.MODE_REALTIME, 1.0
    return c.encode()


def test_a_client_refuses_hostile_clocks_and_takes_over_from_the_last_good_one(procs, tmp_path, child_env, lcm_url):
    lst = Listener(lcm_url)
    s = Proc(node_cmd("S-sim", lcm_url, 9), tmp_path / "S.out", child_env)
    procs.append(s)
    s.wait_text("server for term 1")
    c = Proc(node_cmd("C-sim", lcm_url, 1), tmp_path / "C.out", child_env)
    procs.append(c)
    c.wait_text("joined at global")
    assert lst.pump(10.0, until=lambda: len(lst.msgs["SIM.CLOCK"]) > 5)
    pub = lcm.LCM(lcm_url)
    for stamp, term in ((10**18, 1), (4_000_000_000_000_000, 1), (0, 0), (2**63 - 1, 1)):
        pub.publish("SIM.CLOCK", clock(stamp, term))
    lst.pump(0.5)
    last_good = max(m.utime for _, m in lst.msgs["SIM.CLOCK"] if m.utime < 10**12)
    s.kill()
    c.wait_text("server for term 2")
    assert lst.pump(10.0, until=lambda: sum(m.server_id == "C-sim" for _, m in lst.msgs["SIM.CLOCK"]) >= 5)
    c.stop()
    lst.close()
    mine = [m.utime for _, m in lst.msgs["SIM.CLOCK"] if m.server_id == "C-sim"]
    assert mine == sorted(mine)
    assert last_good <= mine[0] < last_good + 5_000_000, (last_good, mine[:3])  # on its line
    stopped = re.search(r"stopped: .*", c.text()).group(0)
    assert "time drops: invalid 2, jump 1, old_term 1" in stopped, stopped
    assert c.text().count("dropped a message") == 3


def test_garbage_on_the_world_channels_is_counted_in_the_simulators_health(procs, tmp_path, child_env, lcm_url):
    cfg = vehicle_config(tmp_path, "AUV1")
    sim = Proc(sim_cmd(cfg, lcm_url), tmp_path / "sim.out", child_env)
    procs.append(sim)
    sim.wait_text("server for term 1", timeout=30.0)
    lc = lcm.LCM(lcm_url)
    health: list = []
    lc.subscribe("AUV1.HEALTH", lambda _c, d: health.append(process_health_t.decode(d)))
    world = (
        "SIM.CLOCK",
        "SIM.ENV_HEARTBEAT",
        "SIM.ENV_ELECTION",
        "SIM.CLOCK_SYNC",
        "SIM.ENV",
        "SIM.ENV_NEEDS",
        "SIM.LOCKSTEP",
        "SIM.ENV_SAMPLE.AUV1-sim",
    )
    for ch in world:
        lc.publish(ch, b"\x00" * 7)  # truncated
        lc.publish(ch, clock(1, 1)[:-2] if ch != "SIM.CLOCK" else b"\xff" * 40)
    n = 2 * len(world)
    assert pump(lc, lambda: any(h.decode_errors >= n for h in health), timeout=20), [h.decode_errors for h in health]
    k = len(health)
    assert pump(lc, lambda: len(health) > k + 1, timeout=20)  # and it runs on
    assert sim.p.poll() is None
    assert max(h.decode_errors for h in health) == n

"""A frozen environment server resumes (issue 12, item 4): SIGSTOP the server
for longer than the failover timeout, SIGCONT. Another node has taken over
meanwhile; the resumed one must re-confirm before it serves again, so over
the recorded SIM.CLOCK stream global time never runs backwards and no
message of an old term follows one of a newer term. Repeated, each time on
whichever node serves then (real processes over LCM)."""

from __future__ import annotations

import os
import re
import signal

import pytest
from mh_util import (
    Listener,
    Proc,
    node_cmd,
    procs,  # noqa: F401 (a fixture)
)

FREEZES = 4


@pytest.mark.parametrize("mode", [("--mode", "scaled", "--warp", "2")])
def test_a_resumed_server_never_sends_time_backwards(procs, tmp_path, child_env, lcm_url, mode):
    lst = Listener(lcm_url)
    nodes = {}
    for name, prio in (("A-sim", 30), ("B-sim", 20), ("C-sim", 10)):
        nodes[name] = Proc(node_cmd(name, lcm_url, prio, *mode), tmp_path / f"{name}.out", child_env)
        procs.append(nodes[name])
    nodes["A-sim"].wait_text("server for term 1")
    for name in ("B-sim", "C-sim"):
        nodes[name].wait_text("joined at global")
    for k in range(FREEZES):
        server, term = lst.last_server()
        frozen = nodes[server]
        os.killpg(frozen.p.pid, signal.SIGSTOP)
        # frozen until another node serves a newer term (longer than the failover timeout)
        assert lst.pump(20.0, until=lambda: lst.last_server()[1] > term), lst.last_server()
        lst.pump(0.3)
        os.killpg(frozen.p.pid, signal.SIGCONT)
        new_server, new_term = lst.last_server()
        frozen.wait_text(f"client of {new_server} (term {new_term})")
        assert frozen.p.poll() is None
    n = len(lst.msgs["SIM.CLOCK"])
    assert lst.pump(10.0, until=lambda: len(lst.msgs["SIM.CLOCK"]) > n + 5)
    for p in procs:
        p.stop()
    lst.close()
    clock = [m for _, m in lst.msgs["SIM.CLOCK"]]
    back = [
        (a.utime, a.term, a.server_id, b.utime, b.term, b.server_id)
        for a, b in zip(clock, clock[1:])
        if b.utime < a.utime
    ]
    assert not back, f"global time ran backwards: {back}"
    old = [(a.term, a.server_id, b.term, b.server_id) for a, b in zip(clock, clock[1:]) if b.term < a.term]
    assert not old, f"a message of an old term followed a newer one: {old}"
    hb = [(m.server_id, m.term) for _, m in lst.msgs["SIM.ENV_HEARTBEAT"]]
    hb = [x for i, x in enumerate(hb) if i == 0 or hb[i - 1] != x]
    # nor did a resumed server send a heartbeat in its old term (others would follow it)
    assert all(b[1] >= a[1] for a, b in zip(hb, hb[1:])), hb
    assert len({m.term for m in clock}) == FREEZES + 1, (sorted({m.term for m in clock}), hb)
    for name, p in nodes.items():
        text = p.text()
        stopped = re.search(r"stopped: .*", text)
        assert stopped, (name, text)
        # what each node itself took: no value behind its clock within a term.
        # An old term's clock refused is the gate at work, not a fault: a node
        # starved of the CPU can win (or hear) the next term before it drains
        # the last clocks the frozen server sent before it stopped; the
        # listener's order above is what proves no server sent one late.
        assert "regression " not in stopped.group(0).split("time drops")[-1], (name, stopped.group(0))

"""Lockstep: two simulators and their navigator managers (C) in one world,
stepped by the environment server; the same scenario twice gives the same
messages, bit for bit.

What the comparison leaves out, and why (docs/multihil.md):
- the control plane, paced by wall time on purpose: SIM.ENV_HEARTBEAT,
  SIM.ENV_ELECTION, SIM.CLOCK_SYNC (liveness and failure detection), lockstep
  REGISTER messages (repeated each wall second until a clock is heard) and
  LEAVE messages (sent when the test stops a process), and
  <V>.HEALTH (wall-time CPU load);
- one field: chasm_status_t.cycle_cost_us, the CPU time of a cycle;
- messages stamped after the cut-off time: the test stops the processes
  asynchronously, so how far each got past the cut differs;
- repeats: a lockstep clock or STEP_DONE is sent again, byte for byte, when
  no progress followed it for a while (a lost datagram, or a slow step on a
  loaded machine); a message right after the same one on its channel (and
  writer) is the same message, counted once.
Everything else -- every sensor, truth, actuator command, navigator status,
the clock, the environment, the needs and samples, the STEP_DONE reports --
is compared per channel (per writer on the shared SIM.LOCKSTEP and
SIM.ENV_NEEDS, whose writers interleave freely within a step), in order,
byte for byte.
"""

from __future__ import annotations

from collections import defaultdict

from mh_util import Listener, Recorder

from auv import chasm_status_t, lockstep_t
from auvlcm.decode import decode_strict
from auvlcm.types import type_of
from tools.launch.world import VehicleSpec, World

CONTROL_PLANE = ("SIM.ENV_HEARTBEAT", "SIM.ENV_ELECTION", "SIM.CLOCK_SYNC")
REPEATED = ("SIM.CLOCK", "SIM.LOCKSTEP")  # repeated, byte for byte, when a datagram may be lost
CUT_US = 20_000_000
LOCKSTEP = {"lockstep_participants": 4, "step_s": 0.1, "lockstep_timeout_s": 60}


def run_world(out, url, child_env, build, order=("AUV1", "AUV2")) -> dict[str, list[bytes]]:
    world = World(out, url, build, child_env)
    lst = Listener(url)
    rec = Recorder(url)
    specs = {"AUV1": VehicleSpec("AUV1", east_m=0.0), "AUV2": VehicleSpec("AUV2", east_m=30.0)}
    try:
        for v in order:
            world.managers(specs[v])
        # Who serves does not depend on who started first: before a lockstep
        # world's first step the best configured node (priority, then the
        # smaller id: AUV1-sim) takes the role. The test makes the worst case
        # sure: the first simulator serves before the second one starts.
        first, second = order
        world.simulator(specs[first], "lockstep", LOCKSTEP)
        assert lst.pump(60.0, until=lambda: lst.servers() == {f"{first}-sim"}), world.output(f"{first}.sim")
        world.simulator(specs[second], "lockstep", LOCKSTEP)
        done = lst.pump(120.0, until=lambda: any(m.utime > CUT_US + 1_000_000 for _, m in lst.msgs["SIM.CLOCK"][-3:]))
        assert done, {n: world.output(n)[-500:] for n in world.procs}
        assert {m.server_id for _, m in lst.msgs["SIM.CLOCK"]} == {"AUV1-sim"}
    finally:
        world.stop()
        lst.close()
        rec.close()
    per_channel: dict[str, list[bytes]] = defaultdict(list)
    for channel, data in rec.events:
        if channel in CONTROL_PLANE or channel.endswith(".HEALTH") or channel == "LCM_SELF_TEST":
            continue
        m = decode_strict(type_of(data), data)
        if getattr(m, "utime", 0) > CUT_US:
            continue
        if isinstance(m, lockstep_t) and m.kind != lockstep_t.KIND_STEP_DONE:
            continue  # registering (wall-paced) and leaving (the asynchronous end)
        if isinstance(m, chasm_status_t):
            m.cycle_cost_us = 0.0
        # shared channels have several writers whose messages interleave in any order
        # within a step: each writer's sequence is what must be the same
        writer = getattr(m, "participant", "") or (getattr(m, "client_id", "") if channel == "SIM.ENV_NEEDS" else "")
        key = f"{channel}/{writer}" if writer else channel
        data = m.encode()
        if channel in REPEATED and per_channel[key] and per_channel[key][-1] == data:
            continue  # a repeat after a suspected loss (wall-paced): the same message
        per_channel[key].append(data)
    return per_channel


def show(data: bytes) -> dict:
    m = decode_strict(type_of(data), data)
    return {k: getattr(m, k) for k in m.__slots__}


def test_two_lockstep_runs_in_either_start_order_give_identical_messages(tmp_path, lcm_url, child_env, build_dir):
    a = run_world(tmp_path / "a", lcm_url, child_env, build_dir, ("AUV1", "AUV2"))
    b = run_world(tmp_path / "b", lcm_url, child_env, build_dir, ("AUV2", "AUV1"))
    # the world really ran: 200 steps, both vehicles, the navigators flew their plans
    assert len(a["SIM.CLOCK"]) == CUT_US // 100_000 + 1
    for v in ("AUV1", "AUV2"):
        assert len(a[f"{v}.TRUTH"]) >= 190 and len(a[f"{v}.ACTUATORS"]) >= 150
        assert len(a[f"{v}.CHASM.NAVIGATOR"]) >= 190
    for p in ("AUV1.sim", "AUV2.sim", "AUV1.NAVIGATOR", "AUV2.NAVIGATOR"):
        assert len(a[f"SIM.LOCKSTEP/{p}"]) == 201  # STEP_DONE for steps 0..200
    assert a["SIM.ENV_SAMPLE.AUV2-sim"] and a["SIM.ENV_NEEDS/AUV1-sim"]
    assert sorted(a) == sorted(b)
    for ch in sorted(a):
        assert len(a[ch]) == len(b[ch]), f"{ch}: {len(a[ch])} vs {len(b[ch])} messages"
        diff = next((i for i, (x, y) in enumerate(zip(a[ch], b[ch])) if x != y), None)
        assert diff is None, f"{ch}: message {diff} differs: {show(a[ch][diff])} vs {show(b[ch][diff])}"

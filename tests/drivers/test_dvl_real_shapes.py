"""auv-dvl as a process on the PD0 of real instruments' shapes
(python/sim/devices/pd0_shapes.py: WinRiver II's 68 data types and 132 cells,
waves packets between ensembles, an Ocean Surveyor's short leaders, a Sentinel
V): written into a pseudo-terminal in reads of any size, every ensemble is one
dvl_t and nothing is counted as dropped; WinRiver II's count restarted one
back is published (auv-driver-replay on a log of it)."""

from __future__ import annotations

import itertools
import math

from conftest import c_program
from driver_bus import VEHICLE, Bus, Pty, finish, raw_messages, replay_print, start

from auv import dvl_t
from auvlcm import programs
from sim.devices import pd0_shapes

# the shapes with a whole stream of their own (no garbage, no restarted count)
CLEAN = ("waves_between", "winriver_many_types", "ocean_surveyor", "sentinel_v")


def test_the_driver_takes_every_real_shape(lcm_url, tmp_path, child_env):
    data = pd0_shapes.renumber(b"".join(getattr(pd0_shapes, name)() for name in CLEAN), first=1)
    n = sum(1 for r in pd0_shapes.records(data) if r[:2] == b"\x7f\x7f")
    assert n == 6 and sum(1 for r in pd0_shapes.records(data) if r[:2] == b"\x7f\x79") == 3
    bus = Bus(lcm_url, "DVL", dvl_t)
    pty = Pty(tmp_path / "dvl0")
    cmd = programs.device_driver(
        c_program("bin/auv-dvl").parent.parent,
        "dvl",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "dvl0",
        baud=115200,
    )
    proc = start(cmd, tmp_path, child_env)
    try:
        bus.wait_status(lambda s: s.port_open, "the port open")
        at, sizes = 0, itertools.cycle([997, 61, 4096, 1, 300])  # reads of any size
        while at < len(data):
            size = next(sizes)
            pty.write(data[at : at + size])
            at += size
        bus.wait(lambda: len(bus.msgs) >= n, f"{n} dvl_t")
        s = bus.wait_status(lambda s: s.frames_decoded >= n, "every ensemble decoded")
        assert bus.reasons() == {}, s.last_error
        assert s.frames_decoded == n
        assert [d.ensemble for d in bus.msgs] == list(range(1, n + 1))
        # bottom lock where the shape has bottom track (the Sentinel V has none)
        assert [d.mode for d in bus.msgs] == [dvl_t.MODE_BOTTOM_LOCK] * 4 + [dvl_t.MODE_WATER_TRACK] * 2
        for d in bus.msgs:
            assert all(math.isfinite(v) for v in d.velocity_mps) and d.device_utime > 0
        bus.wait(lambda: bus.health and bus.health[-1].decode_errors == 0, "health")
    finally:
        pty.close()
        finish(proc, tmp_path)


def test_a_count_restarted_one_back_is_published(tmp_path, child_env):
    """WinRiver II's ensemble 127, then 127 again minutes later and 128: three
    pings, three dvl_t; the restart counted, nothing refused."""
    raw = raw_messages("DVL", [pd0_shapes.count_restarted()])
    printed, reasons = replay_print(tmp_path, raw, child_env, "DVL")
    assert [p["ensemble"] for p in printed] == ["127", "127", "128"]
    assert reasons == {"ensemble number restarted": 1}, reasons

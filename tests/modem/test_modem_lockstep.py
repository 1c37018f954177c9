"""The modem under lockstep gives the same output whatever order the
processes ran in (issue 14, item 1: the team demo twice gives the same log).

The lockstep barrier guarantees only this much: a request stamped with clock
k reaches its simulator somewhere between that simulator's acceptance of
clock k and of clock k+1; the frame it puts in the water reaches the other
simulators somewhere between their acceptance of clock k+1 and of clock k+2.
Where inside those windows is up to the scheduler. Here one modem node (on
an offline LCM) is driven through the same world many times, each message
handed over at a different point of its window, early or late, and every
run must publish the same messages in the same order: the frames it sends,
what it delivers (arrival times, ranges), its status counts.
"""

from __future__ import annotations

import random

from test_modem_unit import frame, tx_msg

from auv import acoustic_frame_t, modem_rx_t, modem_status_t
from auvlcm.offline import OfflineLcm
from auvlcm.rx import Receiver as LcmReceiver
from sim.environment import Environment, EnvParams
from sim.modem.config import ModemConfig
from sim.modem.node import ModemNode

STEP_US = 100_000  # the lockstep clock
SUB = 5  # physics steps per clock step (50 Hz)
CLOCKS = 60
SPEED = 1.5  # our vehicle runs east [m/s]

# What the other simulators put in the water, stamped with a clock: (clock,
# sender, its position). 30 m away: the wavefront meets us within a physics
# step; 700 m: half a second later. Clock 20: two frames that collide here.
FRAMES = [
    (5, "AUV1", (30.0, 0.0, 10.0)),
    (12, "AUV3", (700.0, 0.0, 10.0)),
    (20, "AUV1", (0.0, 400.0, 10.0)),
    (20, "AUV3", (0.0, -400.0, 10.0)),
    (30, "AUV1", (-250.0, 0.0, 10.0)),
    (41, "AUV3", (60.0, 60.0, 10.0)),
]
# Our own vehicle software's requests, stamped with a clock: clock 30 makes
# us deaf to the frame sent at the same clock.
REQUESTS = [1, 30, 45]


def position(t: float) -> tuple[float, float, float]:
    return (0.0, SPEED * t, 10.0)


def run(rng: random.Random) -> tuple[list[tuple[str, bytes]], modem_status_t]:
    lc = OfflineLcm()
    rx = LcmReceiver(lc)
    clock_us = [0]
    cfg = ModemConfig(peer_reports=False, frame_overhead_s=0.3, loss_at_zero=0.0, loss_at_max_range=0.0)
    env = Environment(EnvParams(sound_speed_mps=1500.0))
    node = ModemNode(cfg, "AUV2", 7, env, rx, lc.publish, clock_now_us=lambda: clock_us[0])
    subs = {s.channel: s for s in rx.subscriptions}

    def feed(channel: str, msg) -> None:
        subs[channel].on_raw(channel, msg.encode())

    # each message: the clock whose acceptance opens its window, and the
    # point in that window it comes at (0 .. SUB: before that physics step)
    arrivals: dict[tuple[int, int], list] = {}
    for k, src, pos in FRAMES:
        f = frame(src=src, seq=k, pos=pos)
        f.utime, f.duration_us = k * STEP_US, 300_000
        arrivals.setdefault((k + 1, rng.randint(0, SUB)), []).append(("SIM.ACOUSTIC", f))
    for k in REQUESTS:
        m = tx_msg(vehicle="AUV2", seq=k)
        m.utime = k * STEP_US
        arrivals.setdefault((k, rng.randint(0, SUB)), []).append(("AUV2.MODEM_TX", m))
    for msgs in arrivals.values():
        rng.shuffle(msgs)  # two senders: no order between them either
    for k in range(1, CLOCKS + 1):
        clock_us[0] = k * STEP_US
        node.clock(k * STEP_US)
        for j in range(SUB + 1):
            for channel, msg in arrivals.get((k, j), []):
                feed(channel, msg)
            if j < SUB:
                t = round((k - 1) * STEP_US / 1e6 + (j + 1) * 0.02, 9)
                node.step(t, position(t))
    return lc.published, node.status


def test_any_order_within_the_barrier_gives_the_same_messages():
    reference, status = run(random.Random(0))
    delivered = [modem_rx_t.decode(d) for ch, d in reference if ch == "AUV2.MODEM_RX"]
    sent = [acoustic_frame_t.decode(d) for ch, d in reference if ch == "SIM.ACOUSTIC"]
    # the world did what it was built to: deliveries, a collision, deafness
    assert [m.seq for m in delivered] == [5, 12, 41], delivered
    assert status.collided == 2 and status.deaf == 1 and status.sent == 3, status
    assert [f.utime for f in sent] == [k * STEP_US for k in REQUESTS]  # at the requests' own stamps
    # arrival and range are the physics', from where we were at the arrival
    for m in delivered:
        k, _, src_pos = next(f for f in FRAMES if f[0] == m.seq)
        t_arr = m.utime / 1e6
        expected = sum((a - b) ** 2 for a, b in zip(src_pos, position(t_arr))) ** 0.5
        assert abs(m.range_m - expected) < SPEED * 0.02 + 1e-6, (m.seq, m.range_m, expected)
        assert abs(t_arr - (k * STEP_US / 1e6 + m.range_m / 1500.0)) < 1e-5
    for seed in range(1, 25):
        published, _ = run(random.Random(seed))
        assert len(published) == len(reference), seed
        for i, (a, b) in enumerate(zip(published, reference)):
            assert a == b, f"order {seed}: message {i} differs: {a[0]} vs {b[0]}"

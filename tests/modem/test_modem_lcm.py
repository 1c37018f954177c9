"""The modem between simulator processes over real LCM, on a stepped clock:
propagation delay, range limit, size and rate limits, and loss against
range. Run inside tests/isolated_net.sh."""

from __future__ import annotations

import math

import pytest
from world import LAG_CLOCKS, STEP_US, World

from sim.modem.acoustics import loss_probability
from sim.modem.config import ModemConfig

C0, GRADIENT = 1490.0, 0.02  # as in world.SIM_CONFIG
LOSSLESS = {"loss_at_zero": 0.0, "loss_at_max_range": 0.0, "max_range_m": 2000}


@pytest.fixture
def world(lcm_url, tmp_path, child_env):
    w = World(lcm_url, tmp_path, child_env)
    yield w
    for proc in w.procs.values():
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def test_delay_is_distance_over_sound_speed_and_range_is_a_hard_limit(world):
    world.add_sim("AUV1", 0.0, 0.0, 10.0, LOSSLESS)
    world.add_sim("AUV2", 600.0, 800.0, 30.0, LOSSLESS)  # ~1000 m from AUV1
    world.add_sim("AUV3", 2100.0, 0.0, 10.0, LOSSLESS)  # 2100 m from AUV1
    world.tick(2)
    t0 = world.utime
    world.send("AUV1", 20)
    world.tick()  # the sender takes it at t0
    world.run_for(1.8)  # beyond 2000 m / c
    sent_from = world.truth["AUV1"][t0]
    ((delivered_tick, rx),) = world.arrived_at["AUV2.MODEM_RX"]
    assert rx.tx_utime == t0 and rx.src_vehicle == "AUV1" and rx.vehicle == "AUV2"
    assert rx.payload == bytes(range(20))
    # the range is from the first step the wavefront reached, wherever the
    # receiver was when the frame came to it
    arrival_tick = min(u for u in world.truth["AUV2"] if u >= rx.utime - 1)
    at = world.truth["AUV2"][arrival_tick]
    d = math.dist(sent_from, at)
    c = C0 + GRADIENT * 0.5 * (sent_from[2] + at[2])
    t_arrival_us = t0 + d / c * 1e6
    assert arrival_tick - STEP_US < t_arrival_us <= arrival_tick
    assert abs(rx.utime - t_arrival_us) <= 1.0
    # judged once every frame up to then is certain to be in: two clocks later
    assert delivered_tick == arrival_tick + LAG_CLOCKS * STEP_US
    assert rx.range_m == pytest.approx(d, abs=1e-6)
    # 2100 m is over max_range_m = 2000: never delivered, counted as such
    assert world.msgs["AUV3.MODEM_RX"] == []
    assert world.status("AUV3").out_of_range == 1 and world.status("AUV3").received == 0
    # the other way round: AUV3 reaches AUV2 (~1700 m) but not AUV1 (2100 m)
    world.send("AUV3", 5, seq=77)
    world.tick()
    world.run_for(1.8)
    assert [m.seq for m in world.msgs["AUV2.MODEM_RX"]] == [1, 77]
    assert [m.seq for m in world.msgs["AUV1.MODEM_RX"]] == []
    assert world.status("AUV1").out_of_range == 1
    outs = world.close()
    assert "1 frames sent" in outs["AUV1"] and "1 out of range" in outs["AUV3"]


def test_unicast_reaches_only_its_addressee(world):
    world.add_sim("AUV1", 0.0, 0.0, 10.0, LOSSLESS)
    world.add_sim("AUV2", 100.0, 0.0, 10.0, LOSSLESS)
    world.add_sim("AUV3", 0.0, 100.0, 10.0, LOSSLESS)
    world.tick(2)
    world.send("AUV1", 8, dst="AUV3")
    world.run_for(0.5)
    assert world.msgs["AUV2.MODEM_RX"] == []
    assert [(m.src_vehicle, m.dst_vehicle) for m in world.msgs["AUV3.MODEM_RX"]] == [("AUV1", "AUV3")]
    world.close()


def test_size_and_rate_limits_refuse_with_a_reason_and_count(world):
    # 400 bps and 0.5 s overhead: a 50-byte frame keeps the modem busy 1.5 s
    world.add_sim("AUV1", 0.0, 0.0, 10.0, {"max_frame_bytes": 64, "bitrate_bps": 400, "frame_overhead_s": 0.5})
    world.tick(2)
    world.send("AUV1", 65, seq=1)
    world.tick()
    assert world.status("AUV1").refused_size == 1
    assert world.status("AUV1").last_refusal == "65 bytes is over max_frame_bytes = 64"
    t_start = world.utime
    world.send("AUV1", 50, seq=2)
    world.tick()
    world.send("AUV1", 10, seq=3)  # 20 ms later: still on the air
    world.tick()
    st = world.status("AUV1")
    assert (st.sent, st.refused_rate, st.last_refused_seq) == (1, 1, 3)
    assert st.last_refusal.startswith("busy: frame 2 is on the air until t = ")
    assert st.busy_until_utime == t_start + 1_500_000
    world.run_for(1.5)  # now it is free again
    world.send("AUV1", 10, seq=4)
    world.tick()
    st = world.status("AUV1")
    assert (st.sent, st.refused_size, st.refused_rate, st.refused_invalid) == (2, 1, 1, 0)
    outs = world.close()
    assert "modem refused frame 1: 65 bytes is over max_frame_bytes = 64" in outs["AUV1"]


def test_loss_rate_against_range_over_lcm(world):
    """Frames to receivers at 300 m and 1500 m: lost at the curve's rates
    (binomial tolerance), and exactly the frames the seeded draw says."""
    cfg = {
        "loss_at_zero": 0.1,
        "loss_at_max_range": 0.7,
        "max_range_m": 2000,
        "bitrate_bps": 100000,
        "frame_overhead_s": 0.0,
    }
    world.add_sim("AUV1", 0.0, 0.0, 10.0, cfg)
    world.add_sim("AUV2", 300.0, 0.0, 10.0, cfg)
    world.add_sim("AUV3", 0.0, 1500.0, 10.0, cfg)
    world.tick(2)
    n = 200
    for _ in range(n):  # one frame per step
        world.send("AUV1", 4)
        world.tick()
    world.run_for(1.2)
    assert world.status("AUV1").sent == n
    mc = ModemConfig(**cfg)
    for vid, range_m in (("AUV2", 300.0), ("AUV3", 1500.0)):
        st = world.status(vid)
        assert st.received + st.lost == n
        p = loss_probability(range_m, mc)
        sigma = math.sqrt(n * p * (1 - p))
        assert abs(st.lost - n * p) < 4 * sigma, (vid, st.lost, n * p)
        assert len(world.msgs[f"{vid}.MODEM_RX"]) == st.received
    world.close()


def lossy_run(url, tmp_path, env) -> list[tuple]:
    w = World(url, tmp_path, env)
    cfg = {"loss_at_zero": 0.3, "loss_at_max_range": 0.6, "bitrate_bps": 100000, "frame_overhead_s": 0.0}
    try:
        w.add_sim("AUV1", 0.0, 0.0, 10.0, cfg)
        w.add_sim("AUV2", 400.0, 300.0, 20.0, cfg)
        w.tick(2)
        for k in range(40):
            w.send("AUV1" if k % 2 else "AUV2", 6, seq=k)
            w.tick(3)
        w.run_for(0.5)
        w.close()
    finally:
        for proc in w.procs.values():
            if proc.poll() is None:
                proc.kill()
    return [
        (ch, m.seq, m.utime, m.tx_utime, m.range_m, m.snr_db, bytes(m.payload))
        for ch in ("AUV1.MODEM_RX", "AUV2.MODEM_RX")
        for m in w.msgs[ch]
    ]


def test_a_stepped_rerun_delivers_the_same_frames_at_the_same_times(tmp_path, child_env):
    from conftest import _ports

    runs = []
    for i in range(2):
        (tmp_path / str(i)).mkdir()
        runs.append(lossy_run(f"udpm://239.255.76.67:{next(_ports)}?ttl=0", tmp_path / str(i), child_env))
    assert runs[0] == runs[1]
    assert 15 < len(runs[0]) < 38  # 40 frames, 32 % lost at 500 m

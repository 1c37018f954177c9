"""The surface radio's model (sim/radio/link.py): line of sight above the
waves, range, rate, latency, loss, and a dive cutting frames on the air."""

from __future__ import annotations

import pytest

from sim.radio.link import SHORE, RadioConfig, RadioLink


def link(**kw) -> RadioLink:
    cfg = RadioConfig(**{"latency_s": 0.01, "frame_overhead_bytes": 0, **kw})
    r = RadioLink(cfg, ["AUV1", "AUV2"])
    r.set_position("AUV1", 100.0, 0.0, 0.0)
    r.set_position("AUV2", 0.0, 200.0, 0.0)
    return r


@pytest.mark.parametrize(
    "depth, waves, clear",
    [(0.0, 0.2, True), (0.39, 0.2, True), (0.41, 0.2, False), (0.0, 1.2, False), (5.0, 0.0, False), (-0.1, 1.0, True)],
)
def test_the_antenna_is_clear_only_above_the_crests(depth, waves, clear):
    r = link(antenna_height_m=0.5, wave_height_m=waves)
    r.set_position("AUV1", 0.0, 0.0, depth)
    assert r.clear("AUV1") is clear and r.up("AUV1", SHORE) is clear


def test_range_to_the_shore_and_between_vehicles():
    r = link(max_range_m=150.0)
    assert r.up("AUV1", SHORE) and not r.up("AUV2", SHORE)
    assert r.range_m("AUV1", "AUV2") == pytest.approx(223.6, abs=0.1) and not r.up("AUV1", "AUV2")
    assert r.send("SHORE", "AUV2", b"x" * 10, 0.0) == "link down"
    assert r.counts[SHORE].dropped == 1


def test_rate_and_latency_set_the_arrival():
    r = link(bitrate_bps=8000.0)  # 1000 bytes per second
    for _ in range(3):
        assert r.send(SHORE, "AUV1", b"x" * 500, 0.0) == ""
    assert r.step(0.5) == []  # the first ends at 0.5 s, arrives at 0.51 s
    got = r.step(0.52)
    assert len(got) == 1 and got[0].t_arrive == pytest.approx(0.51)
    got = r.step(2.0)
    assert [f.t_arrive for f in got] == pytest.approx([1.01, 1.51])
    assert r.counts[SHORE].delivered == 3 and r.counts[SHORE].bytes_delivered == 1500


def test_a_dive_cuts_the_frames_on_the_air_and_the_queue_is_bounded():
    r = link(bitrate_bps=8000.0, queue_bytes=1000)
    assert [r.send(SHORE, "AUV1", b"x" * 400, 0.0) for _ in range(4)] == ["", "", "", "queue full"]
    r.step(0.45)  # the first arrived
    r.set_position("AUV1", 100.0, 0.0, 3.0)  # dived
    assert r.step(5.0) == []
    assert r.drop_reasons == {"queue full": 1, "cut": 1, "link down": 1}


def test_loss_is_drawn_from_the_seed():
    def delivered(seed: int) -> list[int]:
        r = link(loss=0.3, seed=seed, bitrate_bps=1e9)
        out = []
        for i in range(200):
            r.send(SHORE, "AUV1", bytes([i]), i * 1.0)
            out += [f.payload[0] for f in r.step(i + 0.5)]
        return out

    a = delivered(1)
    assert a == delivered(1) and a != delivered(2)
    assert 110 < len(a) < 170

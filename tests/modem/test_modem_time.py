"""The modem against hostile stamps (issue 12, item 3): requests, reports and
frames stamped outside the valid range, from the future of the simulator's
clock, or out of order are dropped and counted; good traffic still flows. The
modem node on an offline LCM, fed through its own typed subscriptions."""

from __future__ import annotations

from test_modem_unit import frame, tx_msg

from auv import acoustic_frame_t, peer_report_t
from auvlcm.offline import OfflineLcm
from auvlcm.rx import Receiver as LcmReceiver
from auvlcm.timepolicy import TimeDrops
from sim.environment import Environment, EnvParams
from sim.modem.config import ModemConfig
from sim.modem.node import ModemNode

HOSTILE = (2**63 - 1, -(2**63), 10**18, -1)


def modem():
    lc = OfflineLcm()
    rx = LcmReceiver(lc)
    lines: list[str] = []
    node = ModemNode(
        ModemConfig(peer_reports=True),
        "AUV2",
        7,
        Environment(EnvParams(sound_speed_mps=1500.0)),
        rx,
        lc.publish,
        TimeDrops("sim: AUV2", lines.append),
    )

    def feed(channel: str, msg) -> None:
        sub = next(s for s in rx.subscriptions if s.channel == channel)
        sub.on_raw(channel, msg.encode())

    return node, feed, lc, lines


def test_hostile_frames_never_wait_in_the_water_and_good_ones_arrive():
    node, feed, lc, lines = modem()
    node.step(10.0, (0.0, 0.0, 10.0))  # the simulator's clock: 10 s
    for bad in HOSTILE:
        feed("SIM.ACOUSTIC", _at(bad, 1))
    feed("SIM.ACOUSTIC", _at(10_000_000 + 5_000_000, 2))  # 5 s from the future
    feed("SIM.ACOUSTIC", _at(9_900_000, 3))  # good: 100 m away, heard soon
    feed("SIM.ACOUSTIC", _at(9_800_000, 4))  # older than the last from AUV1
    assert [f.seq for f in node.rx.pending] == [3]
    for k in range(1, 20):
        node.step(10.0 + k * 0.02, (0.0, 0.0, 10.0))
    rx = [ch for ch, _ in lc.published if ch == "AUV2.MODEM_RX"]
    assert len(rx) == 1 and not node.rx.pending
    assert node.drops.counts["invalid"] == 4 and node.drops.counts["future"] == 1
    assert node.drops.counts["out_of_order"] == 1
    assert len(lines) == 3 and all("SIM.ACOUSTIC from 'AUV1'" in s for s in lines)


def _at(utime: int, seq: int) -> acoustic_frame_t:
    f = frame(src="AUV1", seq=seq, pos=(100.0, 0.0, 10.0))
    f.utime = utime
    return f


def test_hostile_requests_and_reports_are_not_sent():
    node, feed, lc, _ = modem()
    node.step(10.0, (0.0, 0.0, 10.0))
    for i, bad in enumerate(HOSTILE):
        m = tx_msg(vehicle="AUV2", seq=i + 1)
        m.utime = bad
        feed("AUV2.MODEM_TX", m)
        r = peer_report_t()
        r.utime, r.vehicle, r.seq = bad, "AUV2", i + 1
        feed("AUV2.PEER_REPORT", r)
    node.step(10.02, (0.0, 0.0, 10.0))  # requests are handled at the step after they came
    assert not [ch for ch, _ in lc.published if ch == "SIM.ACOUSTIC"]
    good = tx_msg(vehicle="AUV2", seq=9)
    good.utime = 10_000_000
    feed("AUV2.MODEM_TX", good)
    node.step(10.04, (0.0, 0.0, 10.0))
    sent = [data for ch, data in lc.published if ch == "SIM.ACOUSTIC"]
    assert len(sent) == 1 and acoustic_frame_t.decode(sent[0]).utime == 10_000_000  # at its own stamp
    assert node.drops.counts["invalid"] == 8

"""The simulator's Iver3 frontseat (sim.devices.iver3_frontseat, sim.frontseat): its
sentences as auv-frontseat reads them (docs/frontseat.md, "Iver3"), the requests it
takes and refuses, and the `frontseat:` section's checks at file:line:col. The whole
flight against auv-frontseat is tests/drivers/test_frontseat_wire.py."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from confcheck import ConfigError
from sim.config import loads
from sim.devices.emulator import DeviceContext
from sim.devices.frontseat_wire import PAYLOAD
from sim.devices.iver3_frontseat import FT, KN, Iver3Frontseat, Iver3Options, compose
from sim.model import Truth


def emulator(helm_version: int = 5) -> tuple[Iver3Frontseat, list[bytes]]:
    em = Iver3Frontseat(DeviceContext("AUV1", "frontseat", 1, Iver3Options(helm_version=helm_version)))
    sent: list[bytes] = []
    em.send = lambda data, t: sent.append(data)
    return em, sent


def test_a_request_is_taken_in_the_units_of_its_version():
    em, _ = emulator()
    em.receive(compose("OMS,90.0,6.0,30.0,2.9,5"), 1.0)
    rq = em.request
    assert rq is not None and rq.t == 1.0 and rq.timeout_s == 5.0
    assert rq.heading_rad == pytest.approx(math.pi / 2) and rq.depth_m == 6.0
    assert rq.speed_mps == pytest.approx(2.9 * KN)
    old, _ = emulator(helm_version=4)
    old.receive(compose("OMS,0.0,10.0,30.0,2.9,5"), 1.0)
    assert old.request is not None and old.request.depth_m == pytest.approx(10.0 * FT)


def test_bad_requests_are_refused_by_reason():
    em, _ = emulator()
    em.receive(b"$OMS,90.0,6.0,30.0,2.9,5*00\r\n", 0.0)
    em.receive(compose("OMS,400.0,6.0,30.0,2.9,5"), 0.0)
    em.receive(compose("OMS,90.0,x,30.0,2.9,5"), 0.0)
    em.receive(b"$OMS,90.0\r\n", 0.0)
    em.receive(compose("OXX,1"), 0.0)
    assert em.request is None
    assert em.refused == {
        "bad checksum": 1,
        "$OMS out of range": 1,
        "bad $OMS": 2,
        "unknown sentence": 1,
    }
    # the checksum is optional (NMEA 0183): a whole request without one is taken
    em.receive(b"$OMS,90.0,6.0,30.0,2.9,5\r\n", 0.0)
    assert em.request is not None and em.request.heading_rad == pytest.approx(math.pi / 2)


def test_a_poll_is_answered_with_the_compass_and_the_state():
    em, sent = emulator()
    tr = Truth(t=3.0, eta=(0.0, 0.0, 6.096, 0.0, math.radians(-2.0), math.radians(90.0)), nu=(1.5, 0, 0, 0, 0, 0))
    tr.latitude_deg, tr.longitude_deg, tr.altitude_m = 41.5, -70.7, 10.0
    em.truth = tr
    em.report.helm = PAYLOAD
    em.receive(compose("OSD,G,C,S,P,,,,"), 3.0)
    assert len(sent) == 1
    text = sent[0].decode()
    compass, osi = text.split("\r\n")[:2]
    assert compass.startswith("$C90.0P-2.0R0.0T15.0D20.00*")
    f = osi.split("*")[0].split(",")
    assert f[0] == "$OSI" and f[2] == "A" and f[8] == "N" and len(f) == 16
    assert float(f[4]) == 41.5 and float(f[5]) == -70.7 and float(f[6]) == pytest.approx(1.5 / KN, abs=0.01)
    assert float(f[14]) == 90.0 and float(f[15]) == 20.0 and float(f[9]) == pytest.approx(10.0 / FT, abs=0.1)
    # silent: nothing heard, nothing said
    em.silent = True
    em.receive(compose("OSD,G,C,S,P,,,,"), 4.0)
    assert len(sent) == 1


@pytest.mark.parametrize(
    "text, error",
    [
        ("frontseat: {control_min_depth_m: 2}\n", "1:12: frontseat: missing required key 'wire'"),
        ("frontseat: {wire: {protocol: nmea, pty: a}}\n", "frontseat.wire.protocol: expected one of: iver3"),
        ("frontseat: {abort_error: 'S-x', wire: {protocol: iver3, pty: a}}\n", "1:26: frontseat.abort_error"),
        ("frontseat: {wire: {protocol: iver3, pty: a, publish_lcm: true}}\n", "publish_lcm"),
        (
            "frontseat: {wire: {protocol: iver3, pty: a}}\nactuators: {wire: {protocol: maestro, pty: b, table: t}}\n",
            "frontseat: the frontseat commands the fins",
        ),
    ],
)
def test_the_section_is_checked(text, error, tmp_path: Path):
    (tmp_path / "t").write_text("watchdog 0.5\nchannel 0 rudder 1500 500 1100 1900\n")
    with pytest.raises(ConfigError) as exc:
        loads(text, tmp_path / "v.yaml")
    assert any(error in e for e in exc.value.errors), exc.value.errors


def test_a_good_section_is_read(tmp_path: Path):
    cfg = loads(
        "frontseat: {abort_at_s: 30, silent_at_s: 10, silent_for_s: 5, "
        "wire: {protocol: iver3, pty: fs0, baud: 19200, helm_version: 4}}\n",
        tmp_path / "v.yaml",
    )
    fs = cfg.frontseat
    assert fs.abort_at_s == 30 and fs.silent_for_s == 5 and fs.manual_at_s == -1
    assert fs.wire.options.helm_version == 4 and fs.wire.pty == str(tmp_path / "fs0")

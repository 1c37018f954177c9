"""The AHRS emulator's NMEA, read back by an independent parser (pynmea2): PASHR,
HDT and RDI's PRDID parse with a good checksum and carry the measurement's heading, roll
and pitch; VectorNav's VNYMR carries them with the rates, a specific force and a
magnetic field in the body frame; a dropout sends nothing."""

from __future__ import annotations

import math

import pynmea2
import pytest

from sim.devices.ahrs_nmea import DEFAULT_SENTENCES, MAG_NED_GAUSS, AhrsNmea, AhrsNmeaOptions, G, heading_deg
from sim.devices.emulator import DeviceContext
from sim.devices.registry import protocols_of
from sim.model import Truth
from sim.sensors import Ahrs, AhrsConfig


def sample(t=3725.5, roll=math.radians(-12.3), pitch=math.radians(4.56), heading=math.radians(271.0)):
    ahrs = Ahrs(AhrsConfig(), seed=4, vehicle="AUV1")
    tr = Truth(t=t, eta=(0.0, 0.0, 10.0, roll, pitch, heading), nu=(1.0, 0.0, 0.0, 0.01, 0.02, 0.03))
    return ahrs.measure(tr), tr


def emulator(**opts) -> AhrsNmea:
    return AhrsNmea(DeviceContext("AUV1", "ahrs", 4, AhrsNmeaOptions(**opts)))


def test_registered_for_the_ahrs_sensor():
    assert protocols_of("ahrs") == {"nmea": AhrsNmea}


def test_pashr_and_hdt_parse_and_carry_the_measurement():
    msg, tr = sample()
    lines = emulator().encode(msg, tr)
    assert len(lines) == len(DEFAULT_SENTENCES)
    parsed = []
    for raw in lines:
        assert raw.startswith(b"$") and raw.endswith(b"\r\n")
        parsed.append(pynmea2.parse(raw.decode("ascii").strip(), check=True))  # check: the checksum is required
    pashr, hdt = parsed
    assert hdt.talker == "HE" and hdt.sentence_type == "HDT" and hdt.hdg_true == "T"
    assert float(hdt.heading) == pytest.approx(math.degrees(msg.heading_rad) % 360, abs=0.006)
    # pynmea2 reads $PASHR,<time>,... as Ashtech's ATT form
    assert type(pashr).__name__ == "ASHRATT"
    assert pashr.timestamp.isoformat() == "01:02:05.500000+00:00"
    assert float(pashr.true_heading) == pytest.approx(math.degrees(msg.heading_rad) % 360, abs=0.006)
    assert pashr.is_true_heading == "T"
    assert float(pashr.roll) == pytest.approx(math.degrees(msg.roll_rad), abs=0.006)
    assert float(pashr.pitch) == pytest.approx(math.degrees(msg.pitch_rad), abs=0.006)
    assert math.degrees(msg.roll_rad) < 0  # the sign goes through, not only the magnitude
    assert (pashr.roll_accuracy, pashr.pitch_accuracy, pashr.heading_accuracy) == (0.1, 0.1, 0.5)
    assert (pashr.aiding_status, pashr.imu_status) == (0, 1)


def test_prdid_parses_as_rdis_sentence_and_carries_the_measurement():
    msg, tr = sample()
    (raw,) = emulator(sentences=["PRDID"]).encode(msg, tr)
    rdid = pynmea2.parse(raw.decode("ascii").strip(), check=True)
    assert type(rdid).__name__ == "RDID"  # pynmea2's Teledyne RDI sentence: pitch, roll, heading
    assert rdid.pitch == pytest.approx(math.degrees(msg.pitch_rad), abs=0.006)
    assert rdid.roll == pytest.approx(math.degrees(msg.roll_rad), abs=0.006)
    assert rdid.heading == pytest.approx(math.degrees(msg.heading_rad) % 360, abs=0.006)
    assert rdid.roll < 0 < rdid.pitch  # the signs go through


def test_sentences_and_talker_are_configurable():
    msg, tr = sample()
    lines = emulator(sentences=["HDT"], talker="HC").encode(msg, tr)
    assert len(lines) == 1 and lines[0].startswith(b"$HCHDT,")


def test_a_heading_that_rounds_to_360_is_zero():
    assert heading_deg(math.radians(359.999)) == "000.00"
    assert heading_deg(math.radians(-90.0)) == "270.00"


def test_a_dropout_sends_nothing():
    ahrs = Ahrs(AhrsConfig(), seed=4, vehicle="AUV1")
    tr = Truth(t=1.0, eta=(0.0,) * 6, nu=(0.0,) * 6)
    assert emulator().encode(ahrs.dropout_message(tr), tr) == []


def test_problems():
    assert AhrsNmea.problems(AhrsNmeaOptions(sentences=[])) == {"sentences": "name at least one sentence"}
    assert "start_utc" in AhrsNmea.problems(AhrsNmeaOptions(start_utc="2025-02-30T00:00:00Z"))


def vnymr(msg, tr) -> list[float]:
    (raw,) = emulator(sentences=["VNYMR"]).encode(msg, tr)
    text = raw.decode("ascii")
    assert text.startswith("$VNYMR,") and text.endswith("\r\n")
    body, check = text[1:-2].split("*")
    x = 0
    for ch in body.encode():
        x ^= ch
    assert check == f"{x:02X}"  # NMEA's checksum, as VectorNav's
    fields = body.split(",")[1:]
    assert len(fields) == 12 and all(f[0] in "+-" for f in fields)
    assert [len(f.split(".")[1]) for f in fields] == [3] * 3 + [4] * 3 + [3] * 3 + [6] * 3  # VectorNav's widths
    return [float(f) for f in fields]


def test_vnymr_carries_attitude_and_rates():
    msg, tr = sample()
    v = vnymr(msg, tr)
    assert v[0] == pytest.approx((math.degrees(msg.heading_rad) + 180) % 360 - 180, abs=5e-4)
    assert -180.0 <= v[0] <= 180.0 and v[0] < 0  # 271 degrees is yaw -89
    assert v[1] == pytest.approx(math.degrees(msg.pitch_rad), abs=5e-4)
    assert v[2] == pytest.approx(math.degrees(msg.roll_rad), abs=5e-4)
    assert v[9:12] == pytest.approx([msg.p_radps, msg.q_radps, msg.r_radps], abs=5e-7)
    assert math.hypot(*v[3:6]) == pytest.approx(math.hypot(*MAG_NED_GAUSS), abs=2e-4)


def test_vnymr_specific_force_and_field_in_the_body_frame():
    ahrs = Ahrs(AhrsConfig(noise=0.0, bias=0.0, attitude_noise=0.0, rate_noise=0.0), seed=4, vehicle="AUV1")
    still = Truth(t=1.0, eta=(0.0, 0.0, 5.0, 0.0, 0.0, 0.0), nu=(0.0,) * 6)
    v = vnymr(ahrs.measure(still), still)
    assert v[6:9] == pytest.approx([0.0, 0.0, -G], abs=1e-3)  # level and still: -g on z, as the manual's example
    assert v[3:6] == pytest.approx(list(MAG_NED_GAUSS), abs=1e-4)  # heading north: the field as it is
    east_nose_up = Truth(t=1.0, eta=(0.0, 0.0, 5.0, 0.0, math.radians(30), math.pi / 2), nu=(0.0,) * 6)
    v = vnymr(ahrs.measure(east_nose_up), east_nose_up)
    assert v[6] == pytest.approx(G / 2, abs=1e-3)  # nose up: +g sin(pitch) on x
    assert v[4] == pytest.approx(-MAG_NED_GAUSS[0], abs=1e-4)  # heading east: north is to port
    # turning at r while moving at u: the centripetal u r to starboard, plus d nu / dt
    turning = Truth(t=1.0, eta=(0.0,) * 6, nu=(1.5, 0.0, 0.0, 0.0, 0.0, 0.2), nu_dot=(0.1, 0.0, 0.0, 0.0, 0.0, 0.0))
    v = vnymr(ahrs.measure(turning), turning)
    assert v[6:9] == pytest.approx([0.1, 0.3, -G], abs=1e-3)

"""The GPS emulator's NMEA, read back by an independent parser (pynmea2): every
sentence parses with a good checksum, and its values are the measurement's."""

from __future__ import annotations

import math

import pynmea2
import pytest

from auv import gps_fix_t
from sim.devices import nmea
from sim.devices.emulator import DeviceContext
from sim.devices.nmea_gps import SENTENCES, NmeaGps, NmeaGpsOptions
from sim.geo import LocalFrame
from sim.model import Truth
from sim.sensors import Gps, GpsConfig

FRAME = (41.52, -70.67)


def fix_and_truth(t=3725.5, north=1234.5, east=-987.25, depth=0.0, u=1.5, heading=math.radians(60)):
    frame = LocalFrame(*FRAME)
    gps = Gps(GpsConfig(noise=1.0), seed=4, vehicle="AUV1", frame=frame)
    tr = Truth(t=t, eta=(north, east, depth, 0.0, 0.0, heading), nu=(u, 0.0, 0.0, 0.0, 0.0, 0.0))
    return gps.measure(tr), tr


def emulator(**opts) -> NmeaGps:
    return NmeaGps(DeviceContext("AUV1", "gps", 4, NmeaGpsOptions(**opts), LocalFrame(*FRAME)))


def parse_all(lines: list[bytes]) -> dict[str, pynmea2.NMEASentence]:
    out = {}
    for raw in lines:
        assert raw.endswith(b"\r\n") and raw.startswith(b"$")
        msg = pynmea2.parse(raw.decode("ascii").strip(), check=True)  # check: the checksum is required and right
        out[msg.sentence_type] = msg
    return out


def test_every_sentence_parses_and_carries_the_measurement():
    fix, tr = fix_and_truth()
    lines = emulator(speed_noise_mps=0.0).encode(fix, tr)
    assert [raw[3:6].decode() for raw in lines] == list(SENTENCES)
    s = parse_all(lines)
    for name in ("RMC", "GGA"):  # 1e-5 minute of arc is below 2e-7 degree
        assert s[name].latitude == pytest.approx(fix.latitude_deg, abs=2e-7)
        assert s[name].longitude == pytest.approx(fix.longitude_deg, abs=2e-7)
    # sim time 3725.5 s after the default start, 2025-06-01T00:00:00Z
    assert s["GGA"].timestamp.isoformat() == "01:02:05.500000+00:00"
    assert s["RMC"].datestamp.isoformat() == "2025-06-01"
    assert (s["ZDA"].day, s["ZDA"].month, s["ZDA"].year) == (1, 6, 2025)
    assert s["RMC"].status == "A" and s["GGA"].gps_qual == 1
    assert int(s["GGA"].num_sats) == fix.satellites
    assert float(s["GGA"].horizontal_dil) == pytest.approx(fix.hdop)
    assert float(s["GSA"].hdop) == pytest.approx(fix.hdop)
    assert s["GSA"].mode_fix_type == "3"
    assert (s["GGA"].altitude, s["GGA"].altitude_units) == (0.0, "M") and b",0.0,M,0.0,M," in lines[2]
    # 1.5 m/s at 060 degrees true, over ground
    assert float(s["RMC"].spd_over_grnd) == pytest.approx(1.5 * 3600 / 1852, abs=0.01)
    assert float(s["RMC"].true_course) == pytest.approx(60.0, abs=0.1)
    assert float(s["VTG"].spd_over_grnd_kmph) == pytest.approx(5.4, abs=0.01)
    assert float(s["VTG"].true_track) == pytest.approx(60.0, abs=0.1)


def test_south_west_and_the_minute_that_rounds_up():
    e = emulator()
    fix, tr = fix_and_truth()
    fix.latitude_deg, fix.longitude_deg = -(33 + 59.9999999 / 60), -(151 + 0.5 / 60)
    s = parse_all(e.encode(fix, tr))
    raw = s["GGA"]
    assert (raw.lat, raw.lat_dir, raw.lon, raw.lon_dir) == ("3400.00000", "S", "15100.50000", "W")
    assert raw.latitude == pytest.approx(fix.latitude_deg, abs=2e-7)


def test_talker_sentences_and_start_are_configurable():
    fix, tr = fix_and_truth(t=86399.999)
    lines = emulator(talker="GN", sentences=["GGA", "ZDA"], start_utc="2031-12-31T00:00:00Z").encode(fix, tr)
    assert [raw[:6] for raw in lines] == [b"$GNGGA", b"$GNZDA"]
    s = parse_all(lines)
    # 23:59:59.999 rounds to the next day's 00:00:00.00: the date carries
    assert (s["ZDA"].day, s["ZDA"].month, s["ZDA"].year) == (1, 1, 2032)
    assert s["ZDA"].timestamp.isoformat() == "00:00:00+00:00"


def test_checksum_is_the_xor_between_dollar_and_star():
    assert nmea.sentence("GPGLL", ["4916.45", "N", "12311.12", "W", "225444", "A", ""]) == (
        b"$GPGLL,4916.45,N,12311.12,W,225444,A,*1D\r\n"
    )


def test_speed_noise_is_the_emulators_own_stream():
    """A wired GPS measures what an unwired one does: the emulator draws its speed
    noise from its own stream, never the sensor's."""
    frame = LocalFrame(*FRAME)
    tr = Truth(t=1.0, eta=(0.0,) * 6, nu=(1.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    a = Gps(GpsConfig(), 4, "AUV1", frame)
    b = Gps(GpsConfig(), 4, "AUV1", frame)
    e = emulator(speed_noise_mps=0.5)
    for _ in range(5):
        ma, mb = a.measure(tr), b.measure(tr)
        e.encode(mb, tr)
        assert (ma.north_m, ma.east_m) == (mb.north_m, mb.east_m)
    speeds = {parse_all(e.encode(mb, tr))["RMC"].spd_over_grnd for _ in range(3)}
    assert len(speeds) == 3  # and it is noisy


def test_no_fix_under_water_means_no_sentences():
    frame = LocalFrame(*FRAME)
    gps = Gps(GpsConfig(max_depth_m=0.2), 4, "AUV1", frame)
    tr = Truth(t=1.0, eta=(0.0, 0.0, 3.0, 0.0, 0.0, 0.0))
    assert gps.measure(tr) is None  # the Device emits nothing for None (tests/devices/test_wire_line.py)


def test_a_2d_fix_says_so_in_gsa():
    fix, tr = fix_and_truth()
    fix.fix_type = gps_fix_t.FIX_2D
    assert parse_all(emulator().encode(fix, tr))["GSA"].mode_fix_type == "2"

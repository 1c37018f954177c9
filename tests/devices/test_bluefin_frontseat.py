"""The simulator's Bluefin vehicle (sim.devices.bluefin_frontseat behind sim.frontseat):
its sentences as auv-frontseat reads them (docs/frontseat.md, "Bluefin"), the payload's
lines it takes, acknowledges, refuses and counts, and the `frontseat:` section's checks
for it. The whole flight against auv-frontseat is tests/drivers/test_bluefin_wire.py."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from confcheck import ConfigError
from sim.config import loads
from sim.devices.bluefin_frontseat import BluefinFrontseat, BluefinOptions, time_of
from sim.devices.emulator import DeviceContext
from sim.devices.frontseat_wire import MANUAL, MISSION, PAYLOAD, STOPPED, compose
from sim.devices.nmea import checksum
from sim.frontseat import FrontseatConfig, FrontseatVehicle
from sim.model import Truth

LAT, LON = 41.5, -70.75


def emulator(**options) -> tuple[BluefinFrontseat, list[str]]:
    em = BluefinFrontseat(DeviceContext("AUV1", "frontseat", 1, BluefinOptions(**options)))
    sent: list[str] = []
    em.send = lambda data, t: sent.extend(data.decode("ascii").splitlines())
    return em, sent


def truth(t: float = 3.0) -> Truth:
    tr = Truth(
        t=t,
        eta=(0.0, 0.0, 6.25, math.radians(1.5), math.radians(-2.0), math.radians(90.0)),
        nu=(1.5, 0.0, 0.1, 0.0, math.radians(0.5), math.radians(-3.0)),
    )
    tr.latitude_deg, tr.longitude_deg, tr.altitude_m = LAT, LON, 12.34
    return tr


def log_all(em: BluefinFrontseat, t: float = 0.0) -> None:
    for id_ in ("ACK", "NVG", "NVR", "MIS", "CTL", "MSC"):
        em.receive(compose(f"BPLOG,{id_},ON"), t)


def fields(line: str) -> list[str]:
    """A sentence's fields after its checksum is checked."""
    assert line.startswith("$") and line[-3] == "*", line
    body = line[1:-3]
    assert checksum(body) == line[-2:], line
    return body.split(",")


def of(sent: list[str], address: str) -> list[list[str]]:
    return [f for f in map(fields, sent) if f[0] == address]


def test_nothing_is_sent_before_the_payload_asks():
    em, sent = emulator()
    em.truth = truth()
    em.update(0.0)
    em.update(1.0)
    em.receive(compose("BPRMB,000001.000,90.0,6.0,0,1.50,1,0"), 1.0)
    assert sent == [] and em.request is not None  # taken, but no $BFACK: ACK not asked
    em.receive(compose("BPLOG,NVG,ON"), 2.0)
    em.update(2.0)
    assert [f[0] for f in map(fields, sent)] == ["BFNVG"]


def test_navigation_from_the_truth_in_the_tables_format():
    em, sent = emulator()
    log_all(em)
    sent.clear()
    em.truth = truth(3.0)
    em.update(3.0)
    (nvg,) = of(sent, "BFNVG")
    (nvr,) = of(sent, "BFNVR")
    assert len(nvg) == 13 and nvg[1] == "000003.000" and nvg[12] == "000003.000"
    assert nvg[2:6] == ["4130.0000", "N", "07045.0000", "W"] and nvg[6] == "1"
    assert nvg[7:12] == ["12.3", "6.25", "90.0", "1.5", "-2.0"]
    assert len(nvr) == 8
    ve, vn, vd = (float(x) for x in nvr[2:5])
    assert ve == pytest.approx(1.5, abs=0.02) and vn == pytest.approx(0.0, abs=0.02)
    assert vd == pytest.approx(0.1, abs=0.06)
    assert [float(x) for x in nvr[5:8]] == [0.5, 0.0, -3.0]  # pitch, roll, yaw rates
    # at nav_rate_hz (5): the next in 0.2 s, not at every step
    em.update(3.1)
    assert len(of(sent, "BFNVG")) == 1
    em.update(3.2)
    assert len(of(sent, "BFNVG")) == 2


def test_position_format_south_and_east_and_the_time_of_day():
    em, sent = emulator()
    em.receive(compose("BPLOG,NVG,ON"), 0.0)
    tr = truth()
    tr.latitude_deg, tr.longitude_deg = -(12 + 30.12346 / 60), 3 + 59.99999 / 60
    em.truth = tr
    em.update(0.0)
    (nvg,) = of(sent, "BFNVG")
    assert nvg[2:6] == ["1230.1235", "S", "00400.0000", "E"]
    assert time_of(3661.5) == "010101.500" and time_of(86400.25) == "000000.250"


def test_requests_are_acknowledged_processed_refused_or_invalid():
    em, sent = emulator(request_timeout_s=4.0)
    log_all(em)
    sent.clear()
    em.receive(compose("BPRMB,000010.200,90.0,6.0,0,1.50,1,0"), 10.0)
    rq = em.request
    assert rq is not None and rq.t == 10.0 and rq.timeout_s == 4.0 and not rq.stop
    assert rq.heading_rad == pytest.approx(math.pi / 2) and rq.depth_m == 6.0 and rq.speed_mps == 1.5
    em.receive(compose("BPRMB,000011.000,0,0,2,0,0,1"), 11.0)  # Goby3's stop
    assert em.request.stop
    # the vehicle's rules say no: answered 1 with the reason, not flown
    em.judge = lambda t: "above the control depth"
    em.receive(compose("BPRMB,000012.000,180.0,6.0,0,1.50,1,0"), 12.0)
    assert em.request.t == 11.0
    em.judge = lambda t: None
    em.receive(compose("BPRMB,000013.000,180.0,6.0,1,1.50,1,0"), 13.0)  # an altitude: not this vehicle's
    em.receive(compose("BPRMB,000014.000,400.0,6.0,0,1.50,1,0"), 14.0)  # out of range
    em.receive(compose("BPRMB,000015.000,1e2,6.0,0,1.50,1,0"), 15.0)  # no exponent
    em.receive(compose("BPRMB,000016.000,nan,6.0,0,1.50,1,0"), 16.0)
    em.receive(compose("BPRMB,1600,90.0,6.0,0,1.50,1,0"), 16.0)  # bad time
    em.receive(compose("BPRMB,000017.000,90.0,6.0,0,1.50,1"), 17.0)  # a field short
    acks = of(sent, "BFACK")
    assert [(a[2], a[3], a[5], a[7]) for a in acks] == [
        ("RMB", "000010.200", "2", ""),
        ("RMB", "000011.000", "2", ""),
        ("RMB", "000012.000", "1", "above the control depth"),
        ("RMB", "000013.000", "1", "only heading depth and speed"),
        ("RMB", "000014.000", "0", "out of range"),
        ("RMB", "000015.000", "0", "not a number"),
        ("RMB", "000016.000", "0", "not a number"),
        ("RMB", "1600", "0", "expected a time and 6 fields"),
        ("RMB", "000017.000", "0", "expected a time and 6 fields"),
    ]
    assert all(len(a) == 8 and a[1] == time_of(float(a[3][4:6])) for a in acks[:7])
    assert em.requests == 2 and em.refused == {"bad $BPRMB": 5}
    assert em.not_processed == {"above the control depth": 1, "only heading depth and speed": 1}


def test_bad_lines_are_counted_and_dropped():
    em, sent = emulator()
    log_all(em)
    sent.clear()
    em.receive(b"$BPRMB,000010.200,90.0,6.0,0,1.50,1,0*00\r\n", 1.0)
    em.receive(b"$BPRMB,000010.200,90.0\r\n", 1.0)  # no checksum (optional): read, and short
    em.receive(b"$BPRMB,0000\xff10.200*12\r\n", 1.0)
    em.receive(b"$BPRMB,00" + compose("BPSTS,000001.000,1,auv-frontseat"), 1.0)
    em.receive(b"$" + b"9" * 700 + b"\r\n", 1.0)
    em.receive(compose("GPGGA,1"), 1.0)
    em.receive(compose("BP*X,1"), 1.0)
    em.receive(compose("BPABT,000001.000"), 1.0)
    em.receive(compose("BPLOG,XYZ,ON"), 1.0)
    assert em.request is None and em.heartbeats == 1
    assert em.refused == {
        "bad checksum": 1,
        "bad $BPRMB": 1,
        "bad character": 1,
        "truncated": 1,
        "too long": 1,
        "unknown sentence": 2,
        "unsupported sentence": 1,
        "bad $BPLOG": 1,
    }
    assert [(a[2], a[5]) for a in of(sent, "BFACK")] == [("RMB", "0"), ("STS", "2"), ("ABT", "1"), ("LOG", "0")]


def control_words(em: BluefinFrontseat, sent: list[str], helms: list[tuple[float, str]]) -> list[list[str]]:
    em.truth = truth()
    for t, helm in helms:
        em.report.helm = helm
        em.update(t)
    return [f for f in map(fields, sent) if f[0] in ("BFCTL", "BFMSC", "BFMIS")]


def test_control_granted_and_taken_back_with_bfctl():
    em, sent = emulator()
    log_all(em)
    sent.clear()
    words = control_words(em, sent, [(1.0, MISSION), (1.5, PAYLOAD), (1.6, PAYLOAD), (2.0, STOPPED)])
    assert [[w[0], w[-1]] for w in words] == [
        ["BFCTL", "0"],
        ["BFMIS", "Running"],
        ["BFCTL", "1"],
        ["BFCTL", "0"],
        ["BFMIS", "Aborted"],
    ]
    assert words[1] == ["BFMIS", "000001.000", "sim.mis", "Running"]
    # a payload that asks again (a restarted backseat) hears the grant as it stands
    sent.clear()
    em.receive(compose("BPLOG,CTL,ON"), 3.0)
    em.update(3.0)
    assert [[w[0], w[-1]] for w in control_words(em, sent, [])] == [["BFCTL", "0"], ["BFMIS", "Aborted"]]


def test_the_older_firmware_grants_with_bfmsc_and_takes_back_with_bfmis():
    em, sent = emulator(control_sentence="msc")
    log_all(em)
    sent.clear()
    words = control_words(em, sent, [(1.0, PAYLOAD), (2.0, MANUAL)])
    assert [w[0] for w in words] == ["BFMSC", "BFMIS", "BFMIS"]
    assert words[2][3] == "Manual"


def test_silent_it_neither_hears_nor_says():
    em, sent = emulator()
    log_all(em)
    sent.clear()
    em.silent = True
    em.truth = truth()
    em.report.helm = PAYLOAD
    em.receive(compose("BPRMB,000010.200,90.0,6.0,0,1.50,1,0"), 1.0)
    em.update(1.0)
    assert sent == [] and em.request is None
    em.silent = False  # the grant it could not say, said when it speaks again
    em.update(2.0)
    assert [f[0::2] for f in map(fields, sent) if f[0] == "BFCTL"] == [["BFCTL", "1"]]


class _Model:
    """What FrontseatVehicle reads of the vehicle model."""

    def __init__(self, depth: float) -> None:
        self.dt, self.frame, self.depth, self.t = 0.05, None, depth, 0.0
        self.act = type("Act", (), {"stern": 0.0, "rpm": 0.0, "rudder": 0.0})()

    def truth(self, out: Truth) -> Truth:
        tr = truth(self.t)
        tr.eta = (0.0, 0.0, self.depth, 0.0, 0.0, 0.0)
        return tr


class _Devices:
    def add(self, emulator, wire):
        return None


def test_the_vehicles_rules_decide_the_acknowledgement(tmp_path: Path):
    """One set of control rules (sim.frontseat): refused at the surface, granted at depth,
    refused again after the abort; control said with $BFCTL."""
    cfg = loads(
        "frontseat: {control_min_depth_m: 2.0, abort_at_s: 30, wire: {protocol: bluefin, tcp: '127.0.0.1:29500'}}\n",
        tmp_path / "v.yaml",
    ).frontseat
    model = _Model(depth=0.5)
    vehicle = FrontseatVehicle(cfg, _Devices(), "AUV1", 1, model)
    em = vehicle.emulator
    sent: list[str] = []
    em.send = lambda data, t: sent.extend(data.decode("ascii").splitlines())
    log_all(em)

    def step(t: float, request: bool) -> None:
        model.t = t
        if request:
            em.receive(compose(f"BPRMB,{time_of(t)},90.0,6.0,0,1.50,1,0"), t)
        vehicle.command(model)

    step(1.0, True)
    model.depth = 2.5
    step(1.95, False)  # the vehicle's newest step is what a request is judged by
    step(2.0, True)
    step(2.05, False)
    step(31.0, True)
    acks = [(a[5], a[7]) for a in of(sent, "BFACK") if a[2] == "RMB"]
    assert acks == [("1", "above the control depth"), ("2", ""), ("1", "aborted")]
    assert [f[2] for f in of(sent, "BFCTL")] == ["0", "1", "0"]
    assert vehicle.grants == 1 and em.report.helm == STOPPED


@pytest.mark.parametrize(
    "text, error",
    [
        (
            "frontseat: {wire: {protocol: bluefin, tcp: '*:29500', control_sentence: bfctl}}\n",
            "1:73: frontseat.wire.control_sentence: expected one of: ctl, msc",
        ),
        ("frontseat: {wire: {protocol: bluefin, pty: a, nav_rate_hz: 0}}\n", "frontseat.wire.nav_rate_hz"),
        ("frontseat: {wire: {protocol: bluefin, pty: a, helm_version: 4}}\n", "helm_version"),
        ("frontseat: {wire: {protocol: iver3, pty: a, control_sentence: ctl}}\n", "control_sentence"),
        ("frontseat: {wire: {protocol: bluefin, tcp: '*:99999'}}\n", "port must be in [1, 65535]"),
        ("frontseat: {wire: {protocol: bluefn, pty: a}}\n", "expected one of: iver3, bluefin"),
    ],
)
def test_the_bluefin_wire_is_checked(text, error, tmp_path: Path):
    with pytest.raises(ConfigError) as exc:
        loads(text, tmp_path / "v.yaml")
    assert any(error in e for e in exc.value.errors), exc.value.errors


def test_a_good_bluefin_section_is_read(tmp_path: Path):
    fs = loads(
        "frontseat: {wire: {protocol: bluefin, tcp: '*:29500', baud: 115200, control_sentence: msc, "
        "nav_rate_hz: 10, request_timeout_s: 3}}\n",
        tmp_path / "v.yaml",
    ).frontseat
    assert isinstance(fs, FrontseatConfig) and fs.wire.tcp_address == ("", 29500)
    o = fs.wire.options
    assert o.control_sentence == "msc" and o.nav_rate_hz == 10 and o.request_timeout_s == 3

"""The `wire:` settings are checked like every setting: file:line:col errors."""

from __future__ import annotations

import pytest

from confcheck import ConfigError
from sim.config import load


def errors_of(tmp_path, wire: str, sensor: str = "gps") -> list[str]:
    path = tmp_path / "sim.yaml"
    path.write_text(f"sensors:\n  {sensor}:\n    rate_hz: 1\n    wire: {wire}\n")
    with pytest.raises(ConfigError) as exc:
        load(path)
    return [e.replace(f"{path}:", "sim.yaml:") for e in exc.value.errors]


@pytest.mark.parametrize(
    "wire, error",
    [
        (
            "{protocol: nmae, pty: gps0}",
            "sim.yaml:4:22: sensors.gps.wire.protocol: expected one of: nmea, got 'nmae'",
        ),
        (
            "{protocol: nmea, pty: gps0, baud: 9000}",
            "sim.yaml:4:45: sensors.gps.wire.baud: expected one of: 1200, 2400, 4800, 9600, 19200, 38400, "
            "57600, 115200, 230400, 460800, 921600, got 9000",
        ),
        (
            "{protocol: nmea, pty: gps0, tcp: '127.0.0.1:4001'}",
            "sim.yaml:4:11: sensors.gps.wire: give one port: `pty: PATH` or `tcp: HOST:PORT`, not both",
        ),
        ("{protocol: nmea}", "sim.yaml:4:11: sensors.gps.wire: give one port: `pty: PATH` or `tcp: HOST:PORT`"),
        ("{pty: gps0}", "sim.yaml:4:11: sensors.gps.wire: missing required key 'protocol' (one of: nmea)"),
        (
            "{protocol: nmea, tcp: 'localhost:65536'}",
            "sim.yaml:4:33: sensors.gps.wire.tcp: port must be in [1, 65535], got 65536",
        ),
        (
            "{protocol: nmea, tcp: 4001}",
            "sim.yaml:4:33: sensors.gps.wire.tcp: expected a string, got '4001'",
        ),
        (
            "{protocol: nmea, pty: gps0, buad: 4800}",
            "sim.yaml:4:39: sensors.gps.wire.buad: unknown key; did you mean 'baud'?",
        ),
        (
            "{protocol: nmea, pty: gps0, talker: GL}",
            "sim.yaml:4:47: sensors.gps.wire.talker: expected one of: GP, GN, got 'GL'",
        ),
        (
            "{protocol: nmea, pty: gps0, start_utc: '1975-01-01T00:00:00Z'}",
            "sim.yaml:4:50: sensors.gps.wire.start_utc: the year must be in 1980..2079 (two-digit years in RMC)",
        ),
        (
            "{protocol: nmea, pty: gps0, sentences: [GGA, GLL]}",
            "sim.yaml:4:56: sensors.gps.wire.sentences[1]: expected one of: RMC, VTG, GGA, GSA, ZDA, got 'GLL'",
        ),
        (
            "{protocol: nmea, pty: gps0, publish_lcm: maybe}",
            "sim.yaml:4:52: sensors.gps.wire.publish_lcm: expected true/false, got 'maybe'",
        ),
        (
            "[nmea]",
            "sim.yaml:4:11: sensors.gps.wire: expected a mapping: {protocol: ..., pty: PATH | tcp: HOST:PORT, baud: ...}, or false",
        ),
    ],
)
def test_a_bad_wire_names_its_place(tmp_path, wire, error):
    assert errors_of(tmp_path, wire) == [error]


def test_a_sensor_with_no_emulator_says_so(tmp_path):
    assert errors_of(tmp_path, "{protocol: ascii, pty: leak0}", sensor="leak") == [
        "sim.yaml:4:11: sensors.leak.wire: no device emulator speaks for sensors.leak yet"
    ]


def test_good_wires(tmp_path):
    path = tmp_path / "sim.yaml"
    path.write_text(
        "sensors:\n  gps: {wire: {protocol: nmea, tcp: '*:4001', baud: 4800, publish_lcm: false, talker: GN}}\n"
        "  depth: {wire: false}\n"
    )
    cfg = load(path)
    w = cfg.sensors["gps"].wire
    assert (w.tcp_address, w.baud, w.publish_lcm, w.options.talker) == (("", 4001), 4800, False, "GN")
    assert cfg.sensors["depth"].wire is None


def test_two_sensors_on_one_port_are_refused(tmp_path, monkeypatch):
    """Only the GPS has an emulator yet: a stand-in one for the depth sensor."""
    from sim.devices import registry
    from sim.devices.emulator import Emulator

    class Gauge(Emulator):
        sensor, protocol = "depth", "ascii"

    monkeypatch.setattr(registry, "EMULATORS", (*registry.EMULATORS, Gauge))
    path = tmp_path / "sim.yaml"
    path.write_text(
        "sensors:\n"
        "  gps: {wire: {protocol: nmea, tcp: '127.0.0.1:4001'}}\n"
        "  depth: {wire: {protocol: ascii, tcp: '*:4001'}}\n"
        "  ahrs: {}\n"
    )
    with pytest.raises(ConfigError) as exc:
        load(path)
    assert exc.value.errors == [f"{path}:3:17: sensors.depth.wire: sensors.gps is on this port already"]
    path.write_text("sensors:\n  gps: {wire: {protocol: nmea, pty: a}}\n  depth: {wire: {protocol: ascii, pty: b}}\n")
    assert load(path).sensors["depth"].wire.pty == str(tmp_path / "b")


def test_ahrs_and_depth_wires(tmp_path):
    path = tmp_path / "sim.yaml"
    path.write_text(
        "sensors:\n"
        "  ahrs: {wire: {protocol: nmea, pty: ahrs0, talker: HC, sentences: [PASHR]}}\n"
        "  depth: {wire: {protocol: digiquartz, pty: depth0, address: 3, unit: 2}}\n"
    )
    cfg = load(path)
    a, d = cfg.sensors["ahrs"].wire, cfg.sensors["depth"].wire
    assert (a.options.talker, a.options.sentences) == ("HC", ["PASHR"])
    assert (d.options.address, d.options.unit) == (3, 2)
    assert errors_of(tmp_path, "{protocol: digiquartz, pty: d, unit: 9}", sensor="depth") == [
        "sim.yaml:4:48: sensors.depth.wire.unit: must be in [1, 8]"
    ]

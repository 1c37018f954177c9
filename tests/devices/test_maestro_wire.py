"""The fins and thruster at the wire inside the simulator (sim.devices.maestro_wire,
docs/simulator.md "Fins and thruster at the wire"): `actuators.wire` checked like every
wire, its channel table read with auv-servo's rules; with it the simulator does not
take <V>.ACTUATORS (unless `take_lcm`), and the Maestro's pulses, through the table's
inverse, are the actuators' command at each step, ramping as the Maestro ramps; the
stale report holds the Maestro's targets."""

from __future__ import annotations

from pathlib import Path

import pytest

from auv import actuator_state_t
from auvlcm.offline import OfflineLcm
from confcheck import ConfigError
from sim.config import load
from sim.devices.maestro import parse_table
from sim.hil import Simulator

ROOT = Path(__file__).resolve().parents[2]
TABLE = ROOT / "missions" / "hil" / "remus100_fins.table"


def target(ch: int, qus: int) -> bytes:
    return bytes([0x84, ch, qus & 0x7F, qus >> 7])


def write(tmp_path, text: str) -> Path:
    path = tmp_path / "sim.yaml"
    path.write_text(text)
    return path


def errors_of(tmp_path, text: str) -> list[str]:
    with pytest.raises(ConfigError) as exc:
        load(write(tmp_path, text))
    return exc.value.errors


def test_the_committed_table_is_the_remus_100s():
    t = parse_table(TABLE.read_text(), str(TABLE))
    assert t.watchdog_s == 0.5 and not t.pololu
    assert [(c.channel, c.actuator) for c in t.channels] == [(0, "rudder"), (1, "stern_plane"), (2, "prop")]
    # the model's limits inside the pulses: +-20 degrees, +-2450 rpm
    assert t.command([round(4 * (1500 + 1000 * 0.349)), 6000, round(4 * (1500 + 0.2 * 2450))]).prop_rpm == 2450


def test_a_good_wire(tmp_path):
    cfg = load(
        write(tmp_path, f"actuators:\n  wire: {{protocol: maestro, pty: servo0, baud: 115200, table: {TABLE}}}\n")
    )
    w = cfg.actuators.wire
    assert (w.pty, w.baud, w.options.channels, w.options.take_lcm) == (str(tmp_path / "servo0"), 115200, 24, False)
    assert cfg.actuators.table is not None and len(cfg.actuators.table.channels) == 3
    assert load(write(tmp_path, "actuators: {}\n")).actuators.wire is None
    assert load(write(tmp_path, "vehicle: {id: AUV1}\n")).actuators.wire is None


def test_a_bad_wire_names_its_place(tmp_path):
    (tmp_path / "bad.table").write_text("watchdog 0.5\nchannel 0 rudder 1500 -5 1100 1900\n")
    (tmp_path / "ok.table").write_text("watchdog 0.5\nchannel 7 rudder 1500 500 1100 1900\n")
    cases = [
        ("{protocol: maestro, pty: s0}", "2:9: actuators.wire.table: the channel table is required: table: FILE"),
        (
            "{protocol: maestro, pty: s0, table: bad.table}",
            f"2:45: actuators.wire.table: {tmp_path / 'bad.table'}:2:23: microseconds per unit: -5 is outside 0..1e+09",
        ),
        (
            "{protocol: maestro, pty: s0, table: none.table}",
            f"2:45: actuators.wire.table: cannot read the channel table {tmp_path / 'none.table'}: No such file",
        ),
        (
            "{protocol: maestro, pty: s0, table: ok.table, channels: 6}",
            "2:45: actuators.wire.table: channel 7 is beyond a 6-channel Maestro",
        ),
        # an input device publishes nothing: its LCM switch is take_lcm
        (
            "{protocol: maestro, pty: s0, table: ok.table, publish_lcm: false}",
            "2:55: actuators.wire.publish_lcm: unknown",
        ),
        ("{protocol: nmea, pty: s0}", "2:20: actuators.wire.protocol: expected one of: maestro, got 'nmea'"),
    ]
    path = tmp_path / "sim.yaml"
    for wire, error in cases:
        errs = errors_of(tmp_path, f"actuators:\n  wire: {wire}\n")
        assert len(errs) == 1 and errs[0].startswith(f"{path}:{error}"), (wire, errs)


def test_the_fins_and_a_sensor_on_one_port_are_refused(tmp_path):
    errs = errors_of(
        tmp_path,
        f"sensors:\n  ahrs: {{wire: {{protocol: nmea, pty: p0}}}}\nactuators:\n  wire: {{protocol: maestro, pty: p0, table: {TABLE}}}\n",
    )
    assert errs == [f"{tmp_path / 'sim.yaml'}:4:9: actuators.wire: sensors.ahrs is on this port already"]


def sim_with_wire(tmp_path, extra: str = "", take_lcm: bool = False) -> tuple[Simulator, OfflineLcm]:
    text = (
        "simulation: {clock: scaled, duration_s: 3.0, command_timeout_s: 1.0, on_stale: safe}\n"
        "safe_command: {rudder_rad: 0.1, stern_plane_rad: -0.2, prop_rpm: 300}\n"
        "initial: {depth_m: 5.0, prop_rpm: 500}\n"
        'environment: {bathymetry: "flat:depth=50"}\n'
        "sensors: {depth: {}}\n"
        f"actuators:\n  wire: {{protocol: maestro, pty: servo0, table: {TABLE}, take_lcm: {str(take_lcm).lower()}}}\n"
        + extra
    )
    lc = OfflineLcm(keep=True)
    return Simulator(load(write(tmp_path, text)), fast=True, lc=lc), lc


def states(lc: OfflineLcm) -> list[actuator_state_t]:
    return [actuator_state_t.decode(d) for ch, d in lc.published if ch == "AUV1.ACTUATOR_STATE"]


def test_the_pulses_command_the_actuators_and_the_silence_holds_them(tmp_path):
    sim, lc = sim_with_wire(tmp_path)
    try:
        assert "AUV1.ACTUATORS" not in {s.channel for s in sim.rx.subscriptions}
        servo = sim.servo
        assert servo is not None
        # rudder 0.1 rad (1600 us), stern plane -0.05 rad (1450 us), prop 1000 rpm (1700 us)
        servo.receive(target(0, 6400) + target(1, 5800) + target(2, 6800) + bytes([0x90, 0x02]), 0.0)
        assert servo.last_command_t == 0.0
        assert sim.run() == 0
    finally:
        sim.close()
        lc.close()
    a = sim.model.act
    assert a.rudder == pytest.approx(0.1) and a.stern == pytest.approx(-0.05)
    assert a.rpm == pytest.approx(1000.0, abs=1.0)  # the propeller's lag, 10 time constants on
    got = states(lc)
    assert {s.last_command_utime for s in got} == {0}  # the target command, stamped with its sim time
    # stale after command_timeout_s; the Maestro's targets hold, on_stale: safe does not act
    assert sim.stale_events == 1 and got[-1].command_stale
    assert got[-1].rudder_rad == pytest.approx(0.1) and got[-1].prop_rpm == pytest.approx(1000.0, abs=1.0)


def test_before_a_target_the_initial_command_holds_and_the_maestro_ramps(tmp_path):
    sim, lc = sim_with_wire(tmp_path)
    try:
        servo = sim.servo
        assert servo is not None
        assert servo.command_at(0.0).prop_rpm == 0.0  # every channel off: nothing
        # speed 40 (quarter-us per 10 ms) on the rudder: 400 qus (0.1 rad) takes 0.1 s
        servo.receive(target(0, 6000) + bytes([0x87, 0x00, 40, 0]), 0.0)
        servo.receive(target(0, 6400), 1.0)
        assert servo.command_at(1.05).rudder_rad == pytest.approx(0.05)
        assert servo.command_at(1.2).rudder_rad == pytest.approx(0.1)
    finally:
        sim.close()
        lc.close()


def test_take_lcm_subscribes_the_commands_too(tmp_path):
    sim, lc = sim_with_wire(tmp_path, take_lcm=True)
    try:
        assert "AUV1.ACTUATORS" in {s.channel for s in sim.rx.subscriptions}
    finally:
        sim.close()
        lc.close()


def test_the_example_configuration_loads():
    cfg = load(ROOT / "missions" / "hil" / "remus100_wire.yaml")
    assert cfg.actuators.wire.pty == "/tmp/auv1-servo" and cfg.actuators.table is not None
    ahrs = cfg.sensors["ahrs"]
    assert ahrs.wire.options.sentences == ["VNYMR"] and not ahrs.wire.publish_lcm and ahrs.rate_hz == 20

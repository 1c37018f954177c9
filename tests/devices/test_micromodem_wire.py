"""The Micro-Modem at the wire in the simulator (docs/modem.md, "The modem at
the wire"): the `modem.wire` settings checked like every setting, and the
emulator between the host's bytes and the water's frames, I/O-free."""

from __future__ import annotations

import pytest

from auv import modem_rx_t
from confcheck import ConfigError
from sim.config import load
from sim.devices.emulator import DeviceContext
from sim.devices.micromodem import MicroModemOptions, MicroModemWire, parse_table, sentence


def config(tmp_path, wire: str):
    path = tmp_path / "sim.yaml"
    path.write_text(f"vehicle: {{id: AUV1}}\nmodem:\n  profile: fsk80\n  wire: {wire}\n")
    return path


def test_the_modem_wire_is_read_from_the_modem_section(tmp_path):
    cfg = load(config(tmp_path, "{protocol: micromodem, pty: m0, publish_lcm: false, table: 'AUV1=1,AUV2=2'}"))
    w = cfg.modem.wire
    assert (w.protocol, w.publish_lcm, w.options.table, w.options.kind) == ("micromodem", False, "AUV1=1,AUV2=2", 2)
    assert w.pty == str(tmp_path / "m0")  # relative to the configuration's folder
    assert load(config(tmp_path, "false")).modem.wire is None


@pytest.mark.parametrize(
    "wire, error",
    [
        ("{protocol: nmea, pty: m0, table: 'AUV1=1'}", "modem.wire.protocol: expected one of: micromodem"),
        ("{protocol: micromodem, pty: m0}", "modem.wire.table: required: VEHICLE=ADDRESS"),
        ("{protocol: micromodem, pty: m0, table: 'AUV1=1,AUV2=200'}", "modem.wire.table: AUV2: address 200"),
        ("{protocol: micromodem, pty: m0, table: 'AUV1=1', kind: 200}", "modem.wire.kind"),
    ],
)
def test_modem_wire_errors(tmp_path, wire, error):
    with pytest.raises(ConfigError) as exc:
        load(config(tmp_path, wire))
    assert any(error in e for e in exc.value.errors), exc.value.errors


def test_table_rules():
    assert parse_table("AUV1=1,AUV2=2") == {"AUV1": 1, "AUV2": 2}
    for bad in ("AUV1", "AUV1=0", "AUV1=1,AUV1=2", "AUV1=1,AUV2=1", "A B=1"):
        with pytest.raises(ValueError):
            parse_table(bad)


def wired(vehicle: str = "AUV1") -> tuple[MicroModemWire, list[bytes]]:
    emu = MicroModemWire(DeviceContext(vehicle, "modem", 1, MicroModemOptions(table="AUV1=1,AUV2=2,AUV3=3")))
    out: list[bytes] = []
    emu.send = lambda data, t: out.append(data)
    return emu, out


def test_a_packet_becomes_a_frame_and_a_frame_is_printed():
    emu, out = wired()
    emu.receive(sentence("CCCYC,0,1,3,0,0,1"), 10.0)
    assert b"$CACYC,0,1,3,0,0,1" in b"".join(out) and b"$CADRQ,000010,1,3,0,32,1" in b"".join(out)
    emu.receive(sentence("CCTXD,1,3,0,0A0B0C"), 10.2)
    (m,) = emu.take_frames()
    assert (m.vehicle, m.dst_vehicle, m.kind, m.payload, m.utime) == ("AUV1", "AUV3", 2, b"\x0a\x0b\x0c", 10_200_000)
    assert emu.take_frames() == []
    # a broadcast too; an address not in the table is refused, counted
    emu.receive(sentence("CCCYC,0,1,0,0,0,1") + sentence("CCTXD,1,0,0,01"), 11.0)
    emu.receive(sentence("CCCYC,0,1,9,0,0,1") + sentence("CCTXD,1,9,0,01"), 12.0)
    assert [m.dst_vehicle for m in emu.take_frames()] == [""] and emu.refused == 1
    # heard: CACYC, CARXD, CACST at the smallest rate that holds it
    out.clear()
    rx = modem_rx_t()
    rx.vehicle, rx.src_vehicle, rx.dst_vehicle, rx.snr_db = "AUV1", "AUV2", "AUV1", 12.5
    rx.n_bytes, rx.payload = 40, bytes(40)
    emu.hear_frame(20.0, rx)
    text = b"".join(out).decode()
    assert "$CACYC,0,2,1,1,0,1*" in text and "$CARXD,2,1,0,1," + "00" * 40 + "*" in text and "$CACST," in text
    assert emu.heard == 1
    # from a vehicle not in the table: nothing printed
    out.clear()
    rx.src_vehicle = "SHIP"
    emu.hear_frame(21.0, rx)
    assert out == [] and emu.refused == 2


def test_this_vehicle_must_be_in_the_table():
    with pytest.raises(ValueError, match="AUV9 is not in"):
        wired("AUV9")

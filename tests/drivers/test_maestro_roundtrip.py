"""The fins-and-thruster driver's bytes (C: actuator_map + maestro, through
build/bin/auv-maestro-encode) played into the simulator's Maestro emulator (Python:
sim.devices.maestro), in both builds: the pulses the emulator ends with, mapped back
through the same channel table, are the commands the driver was given, clamped to the
limits, and neutral after the watchdog. Both readers of the table agree on its errors."""

from __future__ import annotations

import subprocess

import pytest

from sim.devices.maestro import TableError, parse_table

TABLE = """protocol {protocol}
watchdog 0.5
channel 0 rudder      1500 500 1100 1900
channel 1 stern_plane 1500 500 1100 1900 reversed
channel 2 rudder      1520 480 1100 1900 reversed
channel 5 prop        1490 0.25 1000 2000 speed 200 accel 20
"""


def encode(variant_dir, child_env, tmp_path, table: str, commands: str) -> tuple[bytes, str]:
    path = tmp_path / "fins.table"
    path.write_text(table)
    exe = variant_dir / "bin" / "auv-maestro-encode"
    if not exe.exists():
        pytest.fail(f"{exe} is not built: run `make build sanitize` first")
    p = subprocess.run([str(exe), str(path)], input=commands.encode(), env=child_env, capture_output=True, timeout=60)
    assert p.returncode not in (86, 87), p.stderr.decode()
    return p.stdout, p.stderr.decode() + f"\nexit {p.returncode}"


def play(table_text: str, data: bytes):
    table = parse_table(table_text)
    m = table.maestro()
    assert m.feed(data) == b""  # the driver's commands ask for no reply
    assert m.errors == 0, f"the emulator refused a packet: errors 0x{m.errors:04x}"
    m.advance(2.0)  # long enough for every ramp
    return table, m


@pytest.mark.parametrize("protocol", ["compact", "pololu 12"])
def test_commands_arrive_as_given(variant_dir, child_env, tmp_path, protocol):
    text = TABLE.format(protocol=protocol)
    cmds = "tick 0\ncmd 1000000 1000000 0.25 -0.1 600\ncmd 1100000 1100000 0.3 0.15 -800\n"
    data, log = encode(variant_dir, child_env, tmp_path, text, cmds)
    assert "no command since the start" in log and "applied 2, clamped 0" in log, log
    table, m = play(text, data)
    c = table.command(m.positions())
    assert c.rudder_rad == pytest.approx(0.3, abs=1e-3)
    assert c.stern_plane_rad == pytest.approx(0.15, abs=1e-3)
    assert c.prop_rpm == pytest.approx(-800, abs=1.0)
    # the limits the driver set at the start are the emulator's too
    assert (m.channels[5].speed, m.channels[5].accel) == (200, 20)


def test_clamped_refused_and_watchdog(variant_dir, child_env, tmp_path):
    text = TABLE.format(protocol="compact")
    cmds = (
        "cmd 1000000 1000000 2.0 -2.0 1e6\n"  # past every limit: clamped
        "cmd 1000000 1000001 nan 0 0\n"  # refused: not finite
        "cmd 1000000 900000 0 0 0\n"  # refused: out of order
    )
    data, log = encode(variant_dir, child_env, tmp_path, text, cmds)
    assert "non-finite value" in log and "out of order" in log and "clamped 4" in log, log
    table, m = play(text, data)
    pulses = {ch: m.positions()[ch] / 4 for ch in (0, 1, 2, 5)}
    assert pulses == {0: 1900, 1: 1900, 2: 1100, 5: 2000}
    # then silence past the timeout: neutral, once, and the fins and prop are at zero
    data, log = encode(variant_dir, child_env, tmp_path, text, cmds + "tick 1400000\ntick 1500001\ntick 1600000\n")
    assert log.count("watchdog:") == 1 and "within the watchdog timeout" in log, log
    table, m = play(text, data)
    c = table.command(m.positions())
    assert (c.rudder_rad, c.stern_plane_rad, c.prop_rpm) == (0.0, 0.0, 0.0)


@pytest.mark.parametrize(
    "bad",
    [
        "watchdog 1\nchannel 0 rudder 1500 500 1100 1900\nchannel 0 prop 1500 1 1000 2000\n",
        "watchdog 1\nchannel 0 rudder 1000 500 1100 1900\n",
        "watchdog 1\nchannel 0 rudder 1500 500 1100 1900 speed 0x10\n",
        "watchdog 1\nprotocol pololu 12 13\nchannel 0 rudder 1500 500 1100 1900\n",
        "watchdog 1\n\tchannel 0 rudder 1500 500 1100 1900 # ok\nstern 1\n",
        "watchdog 1e1\n",
    ],
)
def test_both_readers_refuse_alike(variant_dir, child_env, tmp_path, bad):
    _, log = encode(variant_dir, child_env, tmp_path, bad, "")
    with pytest.raises(TableError) as e:
        parse_table(bad, str(tmp_path / "fins.table"))
    assert f"auv-maestro-encode: {e.value}\n" in log and "exit 2" in log, log

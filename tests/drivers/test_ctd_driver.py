"""auv-ctd as a process (c/drivers/ctd, docs/drivers.md "auv-ctd") against the
simulator's SBE 49 FastCAT emulator (python/sim/devices/sbe49.py) on a
pseudo-terminal, in both builds:

- decimal scans with the instrument's salinity (OutputFormat=3, OutputSal=Y): the
  driver publishes ctd_t with the scan's values, to the format's digits, and the
  instrument's salinity; depth by UNESCO 1983 at --latitude; each stamped with its
  line's receive time;
- `--configure 1`: the driver stops the instrument, sets the hex format and starts it
  again; the scans carry no salinity, and the driver's PSS-78 (C) gives what the
  simulator's CTD derived with gsw (TEOS-10's PSS-78), to the hex format's resolution.
"""

from __future__ import annotations

import itertools
import time

import gsw
import pytest
from conftest import c_program
from driver_bus import VEHICLE, Bus, Pty, PtyDevice, finish, start

from auv import ctd_t
from auvlcm import programs
from sim.devices.emulator import DeviceContext
from sim.devices.sbe49 import Sbe49, Sbe49Options


def samples() -> list[ctd_t]:
    """CTD readings across a front, consistent as the simulator's CTD makes them (gsw)."""
    out = []
    for k, (t, s, p) in enumerate([(16.0, 32.5, 5.0), (14.2, 33.4, 6.5), (12.3, 34.4, 8.0), (8.1, 35.0, 30.0)]):
        m = ctd_t()
        m.vehicle, m.valid = VEHICLE, True
        m.temperature_c, m.salinity_psu, m.pressure_dbar = t, s, p
        m.conductivity_s_per_m = float(gsw.C_from_SP(s, t, p)) / 10.0  # mS/cm -> S/m
        m.sound_speed_mps = 1500.0 + k
        out.append(m)
    return out


class Instrument:
    """The emulator behind the pty: a scan each 50 ms of quiet; what the driver writes, it obeys."""

    def __init__(self, pty: Pty, options: Sbe49Options) -> None:
        self.emu = Sbe49(DeviceContext(VEHICLE, "ctd", 5, options))
        self.emu.send = lambda data, t: self._write(pty, data)
        self.pty = pty
        self.heard = bytearray()
        self.next = itertools.cycle(samples())
        self.device = PtyDevice(pty, self._on_data, self._on_idle)

    @staticmethod
    def _write(pty: Pty, data: bytes) -> None:
        try:
            pty.write(data)
        except OSError:
            pass  # nobody on the line yet

    def _on_data(self, data: bytes) -> None:
        self.heard += data
        self.emu.receive(data, time.time())

    def _on_idle(self) -> None:
        for line in self.emu.encode(next(self.next), None):
            self._write(self.pty, line)

    def close(self) -> None:
        self.device.close()


def run_driver(tmp_path, lcm_url, child_env, sanitized, options, flags):
    bus = Bus(lcm_url, "CTD", ctd_t)
    pty = Pty(tmp_path / "ctd0")
    inst = Instrument(pty, options)
    cmd = programs.device_driver(
        c_program("bin/auv-ctd", sanitized).parent.parent,
        "ctd",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "ctd0",
        baud=9600,
        extra=flags,
    )
    before = time.time()
    proc = start(cmd, tmp_path, child_env)
    return bus, pty, inst, proc, before


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_decimal_scans_with_the_instruments_salinity(sanitized, lcm_url, tmp_path, child_env):
    opts = Sbe49Options(output_format=3, output_sal=True, output_sv=False)
    bus, pty, inst, proc, before = run_driver(tmp_path, lcm_url, child_env, sanitized, opts, ["--latitude", "30"])
    try:
        bus.wait(lambda: len(bus.msgs) >= 8, "eight ctd_t")
        after = time.time()
        want = {round(m.temperature_c, 4): m for m in samples()}
        for m in bus.msgs:
            w = want[round(m.temperature_c, 4)]
            assert m.vehicle == VEHICLE and m.valid
            assert m.conductivity_s_per_m == pytest.approx(w.conductivity_s_per_m, abs=5e-6)
            assert m.pressure_dbar == pytest.approx(w.pressure_dbar, abs=5e-4)
            assert m.salinity_psu == pytest.approx(w.salinity_psu, abs=5e-5)  # the instrument's, 4 decimals
            assert m.depth_m == pytest.approx(-float(gsw.z_from_p(w.pressure_dbar, 30.0)), abs=0.01)
            assert m.sound_speed_mps != m.sound_speed_mps  # none sent: NaN, not made up
            assert before * 1e6 <= m.utime <= after * 1e6
        assert bus.reasons() == {}
        assert bytes(inst.heard) == b""  # without --configure the instrument is left alone
    finally:
        inst.close()
        pty.close()
        finish(proc, tmp_path)


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_configure_hex_and_pss78(sanitized, lcm_url, tmp_path, child_env):
    opts = Sbe49Options(output_format=3, output_sal=True, autorun=False)  # stopped, in the other format
    bus, pty, inst, proc, _ = run_driver(tmp_path, lcm_url, child_env, sanitized, opts, ["--configure", "1"])
    try:
        bus.wait(lambda: len(bus.msgs) >= 8, "eight ctd_t")
        assert b"Stop\r\nOutputFormat=1\r\nStart\r\n" in bytes(inst.heard)
        assert inst.emu.output_format == 1 and inst.emu.sampling
        want = {round(m.temperature_c, 4): m for m in samples()}
        for m in bus.msgs:
            w = want[round(m.temperature_c, 4)]
            # PSS-78 in C from the hex scan's C, T, p (resolution 1e-6 S/m, 1e-5 degC) against gsw
            assert m.salinity_psu == pytest.approx(w.salinity_psu, abs=2e-4), (m.salinity_psu, w.salinity_psu)
            assert m.conductivity_s_per_m == pytest.approx(w.conductivity_s_per_m, abs=1e-6)
        assert bus.reasons() == {}
    finally:
        inst.close()
        pty.close()
        finish(proc, tmp_path)

"""`--device` naming what is not a serial line (drv_port.c): a regular file is
a recording, decoded once to its end, never written to (a driver that talks to
its device, the modem, leaves the file as it was), after which the driver
stops by itself; a FIFO is a line without settings, whose writer may go and
come back."""

from __future__ import annotations

import hashlib
import os
import subprocess

from conftest import c_program
from driver_bus import VEHICLE, Bus, finish, start
from test_gps_driver import epoch, nmea

from auv import gps_fix_t, modem_rx_t
from auvlcm import programs


def test_a_file_is_decoded_once_to_its_end_and_the_driver_stops(lcm_url, tmp_path, child_env):
    rec = tmp_path / "day1.nmea"
    rec.write_bytes(epoch("101500.00") + epoch("101501.00", lat="4807.040") + b"$GPGGA,garbage*00\r\n")
    bus = Bus(lcm_url, "GPS", gps_fix_t)
    cmd = programs.device_driver(c_program("bin/auv-gps").parents[1], "gps", vehicle=VEHICLE, lcm_url=lcm_url, port=rec)
    run = subprocess.run(cmd, capture_output=True, text=True, env=child_env, timeout=20)
    assert run.returncode == 0, run.stderr
    assert "read to its end" in run.stderr and "reopen" not in run.stderr.replace("0 reopens", "")
    bus.wait(lambda: len(bus.msgs) == 2 and bus.status, "two fixes and the last status")
    assert [round(m.latitude_deg, 6) for m in bus.msgs] == [round(48 + 7.038 / 60, 6), round(48 + 7.040 / 60, 6)]
    assert bus.reasons() == {"bad checksum": 1}


def test_a_driver_that_talks_writes_nothing_into_a_recording(lcm_url, tmp_path, child_env):
    """auv-modem configures its modem when the port opens ($CCCFG ...): a
    recording takes none of it, and its frames still come out."""
    rec = tmp_path / "modem.log"
    rec.write_bytes(nmea("CARXD,2,1,0,1,48656c6c6f"))
    before = hashlib.sha256(rec.read_bytes()).hexdigest()
    bus = Bus(lcm_url, "MODEM", modem_rx_t, topic="MODEM_RX")
    extra = ["--table", f"{VEHICLE}=1,AUV2=2", "--no-cst"]
    cmd = programs.device_driver(
        c_program("bin/auv-modem").parents[1], "modem", vehicle=VEHICLE, lcm_url=lcm_url, port=rec, extra=extra
    )
    run = subprocess.run(cmd, capture_output=True, text=True, env=child_env, timeout=20)
    assert run.returncode == 0, run.stderr
    bus.wait(lambda: len(bus.msgs) == 1, "the recorded frame")
    assert bytes(bus.msgs[0].payload) == b"Hello" and bus.msgs[0].src_vehicle == "AUV2"
    assert hashlib.sha256(rec.read_bytes()).hexdigest() == before


def test_a_fifo_is_a_line_whose_writer_may_come_back(lcm_url, tmp_path, child_env):
    fifo = tmp_path / "gps.fifo"
    os.mkfifo(fifo)
    bus = Bus(lcm_url, "GPS", gps_fix_t)
    cmd = programs.device_driver(
        c_program("bin/auv-gps").parents[1], "gps", vehicle=VEHICLE, lcm_url=lcm_url, port=fifo
    )
    proc = start(cmd, tmp_path, child_env)
    try:
        bus.wait_status(lambda s: s.port_open, "the FIFO open")
        for k, tod in enumerate(("101500.00", "101501.00")):
            with open(fifo, "wb") as w:  # a writer that goes and comes back
                w.write(epoch(tod))
            bus.wait(lambda: len(bus.msgs) == k + 1, f"fix {k + 1}")
        s = bus.wait_status(lambda s: s.frames_decoded == 4, "both epochs decoded")
        assert s.port_open and s.reopens == 0 and bus.reasons() == {}
    finally:
        finish(proc, tmp_path)

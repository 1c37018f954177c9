"""auv-modem as a process (c/drivers/modem, docs/drivers.md "auv-modem"): the
real driver on a pseudo-terminal against the simulator's Micro-Modem emulator
(python/sim/devices/micromodem.py), a modem_tx_t goes out as CCCYC and CCTXD
and is echoed, a frame the modem prints reaches MODEM_RX with its SNR, and
refusals are counted by reason; then two simulators in lockstep with their
modems at the wire (docs/simulator.md, "Devices at the wire") and a driver
each: a frame from AUV1's MODEM_TX reaches AUV2's MODEM_RX through the water,
the simulators publishing none of the vehicles' modem channels themselves."""

from __future__ import annotations

import math
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import c_program
from driver_bus import VEHICLE, Bus, Pty, PtyDevice, check_usage_errors, finish, start
from lcm_proc import pump

from auv import modem_rx_t, modem_status_t, modem_tx_t
from auvlcm import programs
from sim.devices.micromodem import MicroModem, sentence

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "modem"))  # the modem tests' stepped world
from world import World  # noqa: E402

TABLE = {"AUV1": 1, "AUV2": 2}


class Modem:
    """The emulated modem behind the pty's master (sim time = wall time): what
    the driver writes it reads and answers; every byte the driver wrote is kept."""

    def __init__(self, pty: Pty) -> None:
        self.pty = pty
        self.emu = MicroModem(address=1)
        self.written = bytearray()
        self.device = PtyDevice(pty, self._on_data, self._on_idle)
        self.lock = self.device.lock

    def _on_data(self, data: bytes) -> None:
        self.written += data
        self.pty.write(self.emu.feed(data, time.time()))

    def _on_idle(self) -> None:
        self.pty.write(self.emu.tick(time.time()))

    def says(self, data: bytes) -> None:
        with self.lock:
            self.pty.write(data)

    def lines(self) -> list[str]:
        return bytes(self.written).decode("ascii", "replace").split("\r\n")

    def close(self) -> None:
        self.device.close()


def tx(n_bytes: int, dst: str = "AUV2", seq: int = 1) -> modem_tx_t:
    m = modem_tx_t()
    m.utime, m.vehicle, m.dst_vehicle, m.seq = int(time.time() * 1e6), "", dst, seq
    m.kind, m.n_bytes, m.payload = modem_tx_t.KIND_TEAM, n_bytes, bytes(range(0x40, 0x40 + n_bytes))
    return m


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_modem_on_a_pty(sanitized, lcm_url, tmp_path, child_env):
    bus = Bus(lcm_url, "MODEM", modem_rx_t, topic="MODEM_RX")
    statuses: list[modem_status_t] = []
    bus.collect(f"{VEHICLE}.MODEM_STATUS", modem_status_t, statuses)
    pty = Pty(tmp_path / "modem0")
    modem = Modem(pty)
    cmd = programs.device_driver(
        c_program("bin/auv-modem", sanitized).parent.parent,
        "modem",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "modem0",
        baud=19200,
        extra=programs.modem_flags(TABLE),
    )
    proc = start(cmd, tmp_path, child_env)
    try:
        # opened: our address and CACST, then the question back
        bus.wait(lambda: "$CCCFQ,SRC*3A" in modem.lines(), "the configuration written")
        assert modem.lines()[:3] == ["$CCCFG,SRC,1*31", "$CCCFG,CST,1*37", "$CCCFQ,SRC*3A"]
        s = bus.wait_status(lambda s: s.port_open, "the port open")
        assert s.device == "MODEM" and s.port == f"{tmp_path / 'modem0'}@19200"
        # a frame: the cycle, the data on the modem's request, the echo counted
        bus.lc.publish(f"{VEHICLE}.MODEM_TX", tx(5).encode())
        bus.wait(lambda: statuses and statuses[-1].sent == 1, "the frame sent")
        assert "$CCCYC,0,1,2,0,0,1*5B" in modem.lines()
        assert any(line.startswith("$CCTXD,1,2,0,4041424344*") for line in modem.lines())
        with modem.lock:
            (packet,) = modem.emu.take_outbox()
        assert (packet.src, packet.dest, packet.rate, packet.frames) == (1, 2, 0, [bytes(range(0x40, 0x45))])
        st = statuses[-1]
        assert st.modem_address == 1 and st.rate == 0 and st.busy_until_utime == 0
        # a frame heard: CACYC, CARXD, CACST; published with the CACST's SNR
        before = int(time.time() * 1e6)
        with modem.lock:
            heard = modem.emu.hear(time.time(), 2, 1, 0, [b"\x01\x02\xfe"], 11.5)
        modem.says(heard)
        bus.wait(lambda: len(bus.msgs) >= 1, "a modem_rx_t")
        (rx,) = bus.msgs
        assert (rx.vehicle, rx.src_vehicle, rx.dst_vehicle, rx.kind) == ("AUV1", "AUV2", "AUV1", 2)
        assert rx.payload == b"\x01\x02\xfe" and rx.snr_db == pytest.approx(11.5)
        assert rx.tx_utime == 0 and math.isnan(rx.range_m) and rx.utime >= before
        # refusals, each by its reason: a frame over rate 0's 32 bytes, a bad checksum
        bus.lc.publish(f"{VEHICLE}.MODEM_TX", tx(33, seq=2).encode())
        modem.says(sentence("CARXD,2,1,0,1,AB").replace(b"*", b"0*", 1))
        want = {"frame over the rate's size": 1, "bad checksum": 1}
        s = bus.wait_status(lambda s: sum(s.reason_count) >= 2, "the refusals counted")
        assert bus.reasons() == want, s.last_error
        bus.wait(lambda: statuses[-1].refused_size == 1, "refused_size")
        assert statuses[-1].last_refused_seq == 2 and "33 bytes" in statuses[-1].last_refusal
        bus.wait(lambda: bus.health and bus.health[-1].decode_errors == 2, "health's decode_errors")
        assert bus.health[-1].process == "auv-modem"
        # once a second, counts changing or not
        n = len(statuses)
        pump(bus.lc, lambda: len(statuses) >= n + 2, 4.0)
        assert len(statuses) >= n + 2
    finally:
        modem.close()
        pty.close()
        text = finish(proc, tmp_path)
    assert "frame over the rate's size" in text


def test_usage(child_env):
    exe = str(c_program("bin/auv-modem"))
    p = subprocess.run([exe, "--help"], capture_output=True, text=True, env=child_env, timeout=30)
    assert p.returncode == 0 and "--table" in p.stdout and "MODEM_TX" in p.stdout
    check_usage_errors(
        "bin/auv-modem",
        [
            (["--table", "AUV1=1,AUV2=0"], "--table wants VEHICLE=ADDRESS"),
            (["--table", "AUV1=1,AUV1=2"], "given twice"),
            (["--table", "AUV1"], "--table wants"),
            (["--table", "AUV1=1", "--rate", "9"], "--rate wants"),
            (["--table", "AUV1=1", "--ack-timeout", "-1"], "--ack-timeout wants"),
        ],
        child_env,
        base=["--device", "/dev/null", "--vehicle", "AUV1"],
    )
    # no table, or one without this vehicle: refused at start
    for extra in ([], ["--table", "AUV2=2"]):
        p = subprocess.run(
            [exe, "--device", "/dev/null", "--vehicle", "AUV1", "--lcm-url", "udpm://239.255.76.67:7667?ttl=0", *extra],
            capture_output=True,
            text=True,
            env=child_env,
            timeout=30,
        )
        assert p.returncode == 1 and ("--table" in p.stderr or "not in the address table" in p.stderr), p.stderr


def test_two_vehicles_through_the_water(lcm_url, tmp_path, child_env):
    """Two simulators in lockstep, each modem at the wire only (publish_lcm:
    false), a driver on each: AUV1's frame reaches AUV2's MODEM_RX."""
    world = World(lcm_url, tmp_path, child_env)
    table = ",".join(f"{v}={a}" for v, a in TABLE.items())
    drivers = {}
    try:
        for vid, north in (("AUV1", 0.0), ("AUV2", 300.0)):
            wire = f"{{protocol: micromodem, pty: {vid}-modem, baud: 19200, publish_lcm: false, table: '{table}'}}"
            lossless = {"loss_at_zero": 0.0, "loss_at_max_range": 0.0, "profile": "fsk80", "wire": wire}
            world.add_sim(vid, north, 0.0, 10.0, lossless)
        for vid in TABLE:
            cmd = programs.device_driver(
                c_program("bin/auv-modem").parent.parent,
                "modem",
                vehicle=vid,
                lcm_url=lcm_url,
                port=tmp_path / f"{vid}-modem",
                baud=19200,
                clock="sim",
                extra=programs.modem_flags(TABLE),
            )
            drivers[vid] = start(cmd, tmp_path, child_env, name=vid)
        status = world.msgs

        def wait_ticking(until, what: str, steps: int) -> None:
            for _ in range(steps):
                if until():
                    return
                world.tick()
                time.sleep(0.003)  # the drivers answer in wall time, between steps
            assert until(), f"{what} within {steps} steps"

        # both drivers on the world's clock, each modem configured (its status from the driver)
        wait_ticking(
            lambda: all(any(s.modem_address == a for s in status[f"{v}.MODEM_STATUS"]) for v, a in TABLE.items()),
            "both drivers' statuses",
            500,
        )
        m = tx(12)
        m.utime = world.utime
        world.lc.publish("AUV1.MODEM_TX", m.encode())
        wait_ticking(lambda: status["AUV2.MODEM_RX"], "the frame at AUV2", 1500)
        (rx,) = status["AUV2.MODEM_RX"]
        assert (rx.vehicle, rx.src_vehicle, rx.dst_vehicle) == ("AUV2", "AUV1", "AUV2")
        assert rx.payload == bytes(range(0x40, 0x4C)) and rx.kind == modem_tx_t.KIND_TEAM
        assert math.isfinite(rx.snr_db) and rx.tx_utime == 0  # a driver's: a simulator's would carry tx_utime
        assert any(s.sent == 1 for s in status["AUV1.MODEM_STATUS"])
        # the simulators published none of the vehicles' modem channels: every status is a driver's
        for vid, a in TABLE.items():
            assert all(s.modem_address == a and s.rate == 0 for s in status[f"{vid}.MODEM_STATUS"])
        assert status["AUV1.MODEM_RX"] == []
        texts = {vid: finish(proc, tmp_path, name=vid) for vid, proc in drivers.items()}
        drivers.clear()
        outs = world.close()
        assert "1 frames sent" in outs["AUV1"] and "1 received" in outs["AUV2"], outs
        assert "modem micromodem on pty" in outs["AUV2"] and "1 frames to the host" in outs["AUV2"], outs
        assert "Sanitizer" not in "".join(texts.values())
    finally:
        for proc in [*drivers.values(), *world.procs.values()]:
            if proc.poll() is None:
                proc.kill()
                proc.wait()

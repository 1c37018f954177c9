"""auv-payload as a process (c/drivers/payload, docs/drivers.md "auv-payload"): the
real simulator with its sidescan wired (a pty, LCM too) and its identify sensor
wired (TCP, LCM instead), each read by the real driver on a vehicle LCM of its
own: every contact reaches <V>.CONTACTS byte for byte as the simulator
published it, the looks reach <V>.LOOKS and not the simulator's LCM; a hostile
stream on a pty is counted per reason and publishes nothing."""

from __future__ import annotations

import subprocess
import time

import lcm
from conftest import c_program, fresh_url
from driver_bus import free_tcp_port
from lcm_proc import pump, start_simulator, stop
from test_gps_driver import Pty, finish, start

from auv import driver_status_t, reacquire_look_t, sidescan_contact_t
from auvlcm import programs
from sim.devices.lcmframe import SYNC, crc16, frame

VEHICLE = "AUV1"

CONFIG = """
vehicle: {{id: AUV1}}
simulation: {{clock: scaled, warp: 4, duration_s: 120}}
initial: {{depth_m: 5.0, speed_mps: 1.5, prop_rpm: 1500}}
environment: {{seed: 3, bathymetry: "flat:depth=10"}}
sensors: {{depth: {{}}}}
sonar:
  pd_max: 1.0
  false_alarms_per_km2: 0
  max_attitude_rad: 1.5  # no pilot: the vehicle pitches down and turns, still imaging
  targets: {{file: targets.csv}}
  wire: {{protocol: lcmframe, pty: son0, baud: 115200, publish_lcm: true}}
identify:
  period_s: 0.5
  p_identify: 1.0
  wire: {{protocol: lcmframe, tcp: "127.0.0.1:{tcp}", baud: 115200, publish_lcm: false}}
"""
# along the first 8 m of the (pilotless) track: the sidescan's (8 m abeam, past its
# nadir gap of one altitude) and the identify sensor's (within its 6 m)
TARGETS = [(1, 3.0, 8.0), (2, 4.0, -8.0), (3, 5.0, 9.0), (4, 6.0, -9.0), (5, 5.0, 2.0), (6, 7.0, -1.0)]


class Bus:
    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.raw: dict[str, list[bytes]] = {"CONTACTS": [], "LOOKS": []}
        self.status: list[driver_status_t] = []
        for topic in self.raw:
            self.lc.subscribe(f"{VEHICLE}.{topic}", lambda c, d, t=topic: self.raw[t].append(d)).set_queue_capacity(
                10000
            )
        self.lc.subscribe(
            f"{VEHICLE}.DRIVER.PAYLOAD", lambda c, d: self.status.append(driver_status_t.decode(d))
        ).set_queue_capacity(10000)

    def reasons(self) -> dict[str, int]:
        s = self.status[-1]
        return dict(zip(s.reason, s.reason_count))


def test_contacts_and_looks_over_the_links(tmp_path, child_env, lcm_url):
    sim_url, veh_url = fresh_url(), lcm_url
    (tmp_path / "targets.csv").write_text(
        "id,north_m,east_m,kind,length_m\n" + "".join(f"{i},{n},{e},mine_like,1.0\n" for i, n, e in TARGETS)
    )
    tcp = free_tcp_port()
    cfg = tmp_path / "sim.yaml"
    cfg.write_text(CONFIG.format(tcp=tcp))
    sim_bus, veh_bus = Bus(sim_url), Bus(veh_url)
    sim = start_simulator(cfg, child_env, "--lcm-url", sim_url)
    build = c_program("bin/auv-payload").parents[1]
    son = programs.device_driver(build, "payload", vehicle=VEHICLE, lcm_url=veh_url, port=tmp_path / "son0")
    ident = programs.device_driver(build, "payload", vehicle=VEHICLE, lcm_url=veh_url, tcp=f"127.0.0.1:{tcp}")
    drivers = [start(son, tmp_path, child_env)]
    (tmp_path / "driver.stderr").rename(tmp_path / "sonar.stderr")
    drivers.append(start(ident, tmp_path, child_env))
    try:
        # the vehicle passes the last target (7 m north) in some 6 sim s: 1.5 s at warp 4
        end = time.monotonic() + 30
        while time.monotonic() < end and (len(veh_bus.raw["CONTACTS"]) < 3 or len(veh_bus.raw["LOOKS"]) < 4):
            veh_bus.lc.handle_timeout(20)
            sim_bus.lc.handle_timeout(0)
        pump(sim_bus.lc, lambda: len(sim_bus.raw["CONTACTS"]) >= len(veh_bus.raw["CONTACTS"]), 5)
    finally:
        texts = [finish(drivers[1], tmp_path)]
        (tmp_path / "sonar.stderr").rename(tmp_path / "driver.stderr")
        texts.append(finish(drivers[0], tmp_path))
        rc = stop(sim)
        out = sim.stdout.read() if sim.stdout else ""
        assert rc == 0, out
    contacts, looks = veh_bus.raw["CONTACTS"], veh_bus.raw["LOOKS"]
    assert len(contacts) >= 3 and len(looks) >= 4, (len(contacts), len(looks))
    # what the simulator published (publish_lcm: true), byte for byte and in order (from
    # the first the driver heard: a detection before it opened the link is unheard)
    published = sim_bus.raw["CONTACTS"]
    first = published.index(contacts[0])
    assert contacts == published[first : first + len(contacts)]
    for d in contacts:
        assert sidescan_contact_t.decode(d).vehicle == VEHICLE
    # the looks only at the wire (publish_lcm: false), each a whole reacquire_look_t
    assert sim_bus.raw["LOOKS"] == []
    ids = [reacquire_look_t.decode(d).look_id for d in looks]
    assert ids == list(range(ids[0], ids[0] + len(ids)))  # none lost once connected
    for text in texts:  # a reader that joins mid-frame sees that frame's tail: garbage, nothing else
        drops = [line for line in text.splitlines() if "dropped:" in line]
        assert all("dropped: garbage" in line for line in drops), text


def test_hostile_stream_counted(tmp_path, child_env, lcm_url):
    bus = Bus(lcm_url)
    pty = Pty(tmp_path / "pay0")
    build = c_program("bin/auv-payload").parents[1]
    cmd = programs.device_driver(
        build,
        "payload",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "pay0",
        extra=programs.payload_flags(frame_timeout_s=0.2),
    )
    proc = start(cmd, tmp_path, child_env)
    c = sidescan_contact_t()
    c.utime, c.vehicle, c.contact_id, c.classification = 1_000_000, VEHICLE, 1, "unknown"
    good = frame("CONTACTS", c.encode())
    bad_crc = bytearray(good)
    bad_crc[-1] ^= 0xFF
    look = reacquire_look_t()
    look.vehicle = VEHICLE
    too_long = SYNC + b"\x01X" + (5000).to_bytes(2, "big")
    try:
        assert pump(bus.lc, lambda: bool(bus.status) and bus.status[-1].port_open, 20)
        pty.write(b"\x00\x01junk" + good + bytes(bad_crc) + good + frame("SONAR", c.encode()))
        pty.write(frame("CONTACTS", look.encode()) + good + too_long + good + good[:9])
        want = {
            "garbage": 1,
            "bad crc": 1,
            "unknown topic": 1,
            "undecodable": 1,
            "too long": 1,
            "truncated frame": 1,
        }
        ok = pump(bus.lc, lambda: bool(bus.status) and sum(bus.status[-1].reason_count) >= len(want), 20)
        assert ok and bus.reasons() == want, bus.status[-1] if bus.status else None
        assert bus.raw["CONTACTS"] == [good[5 + 8 : -2]] * 4
        assert bus.status[-1].frames_decoded == 4 and crc16(good[:-2]) == int.from_bytes(good[-2:], "big")
    finally:
        pty.close()
        finish(proc, tmp_path)


def test_usage_errors(child_env):
    exe = str(c_program("bin/auv-payload"))
    for args, text in [
        (["--frame-timeout", "0"], "--frame-timeout wants seconds"),
        (["--frame-timeout", "x"], "wants"),
    ]:
        p = subprocess.run(
            [exe, "--device", "/dev/null", "--vehicle", "A", *args],
            capture_output=True,
            text=True,
            env=child_env,
            timeout=30,
        )
        assert p.returncode == 2 and text in p.stderr, (args, p.stderr)

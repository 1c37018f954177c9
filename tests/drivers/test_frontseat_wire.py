"""A commercial vehicle's frontseat, end to end (docs/frontseat.md): a running simulator
whose vehicle is flown by its frontseat (`frontseat:`, the emulator on a port), the
real auv-frontseat on that port (`--clock sim`), and setpoint_t published on LCM as
the navigator would. The request is refused at the surface (the frontseat dives on its
own mission first) and granted at depth; the simulated vehicle turns to the heading
and reaches the depth; the frontseat's <V>.NAV matches the simulator's truth within
the protocol's resolution; its operator's abort takes control back.

Iver3 (both builds, on a pseudo-terminal): also a setpoint over the limits clamped,
one under them refused, each with its reason, and the frontseat's silence. Bluefin
(the sanitized build, on TCP as Huxley is reached): the refusal is the vehicle's own
($BFACK status 1 with its reason), the grant its $BFCTL."""

from __future__ import annotations

import math
import subprocess
import time
from collections.abc import Iterator
from contextlib import contextmanager

import lcm
import pytest
from conftest import c_program
from driver_bus import finish, free_tcp_port, start
from lcm_proc import pump, stop

from auv import driver_status_t, frontseat_status_t, ground_truth_t, nav_solution_t, setpoint_t, sim_clock_t
from auvlcm import programs

VEHICLE = "AUV1"
ORIGIN = (41.52, -70.67)  # the simulator's default world origin (sim.environment.EnvParams)
# sim time [s]; the flight to 6 m takes some 30 s. At 8 times real time a loaded test
# may lag its simulator: its setpoints, stamped with the newest SIM.CLOCK it read,
# are refused stale only after 5 s (--setpoint-timeout, 0.6 s of wall time)
SILENT_AT, SILENT_FOR, ABORT_AT = 45.0, 6.0, 60.0
WARP = 8.0
SETPOINT_TIMEOUT_S = 5.0


def config(wire: str, *, warp: float, abort_at: float, silent_at: float = -1.0, silent_for: float = 0.0) -> str:
    """The simulator's file: a vehicle at the surface whose frontseat (`wire`) dives on
    its own mission to 4 m, takes requests from 2 m, and aborts at `abort_at`."""
    return f"""
vehicle: {{id: {VEHICLE}}}
simulation: {{clock: scaled, warp: {warp}, truth_rate_hz: 20}}
initial: {{depth_m: 0.0, speed_mps: 1.0, heading_rad: 0.0}}
environment: {{bathymetry: "flat:depth=50", waves: {{height_m: 0.0}}}}
sensors: {{depth: {{}}}}
frontseat:
  control_min_depth_m: 2.0
  mission_heading_deg: 0.0
  mission_depth_m: 4.0
  mission_speed_mps: 1.5
  silent_at_s: {silent_at}
  silent_for_s: {silent_for}
  abort_at_s: {abort_at}
  abort_error: Stl
  wire: {wire}
"""


class Bus:
    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.clock = 0
        self.truth: list[ground_truth_t] = []
        self.nav: list[nav_solution_t] = []
        self.fs: list[frontseat_status_t] = []
        self.driver: list[driver_status_t] = []
        self.want = (math.pi / 2, 6.0, 1.5)

        def on_clock(_c, d):
            self.clock = max(self.clock, sim_clock_t.decode(d).utime)

        subs = (
            ("SIM.CLOCK", on_clock),
            (f"{VEHICLE}.TRUTH", lambda c, d: self.truth.append(ground_truth_t.decode(d))),
            (f"{VEHICLE}.NAV", lambda c, d: self.nav.append(nav_solution_t.decode(d))),
            (f"{VEHICLE}.FRONTSEAT", lambda c, d: self.fs.append(frontseat_status_t.decode(d))),
            (f"{VEHICLE}.DRIVER.FRONTSEAT", lambda c, d: self.driver.append(driver_status_t.decode(d))),
        )
        for channel, fn in subs:
            self.lc.subscribe(channel, fn).set_queue_capacity(100000)
        self._last_sp = 0

    def reason(self, name: str) -> int:
        if not self.driver:
            return 0
        s = self.driver[-1]
        return dict(zip(s.reason, s.reason_count)).get(name, 0)

    def setpoint(self, heading: float, depth: float, speed: float) -> None:
        m = setpoint_t()
        m.utime, m.vehicle = self.clock, VEHICLE
        m.heading_rad, m.depth_m, m.speed_mps = heading, depth, speed
        m.vertical_mode, m.speed_mode = setpoint_t.VERTICAL_DEPTH, setpoint_t.SPEED_MPS
        self.lc.publish(f"{VEHICLE}.SETPOINT", m.encode())

    def wait(self, until, what: str, timeout: float = 60.0) -> None:
        """Handle messages until until(), asking for self.want at 5 Hz of sim time."""

        def step() -> bool:
            if self.want is not None and self.clock - self._last_sp >= 200_000 and self.clock > 0:
                self._last_sp = self.clock
                self.setpoint(*self.want)
            return until()

        ok = pump(self.lc, step, timeout)
        assert ok, f"waited {timeout} s for {what}; last status {self.fs[-1:]}, truth {self.truth[-1:]}"

    def truth_at(self, utime: int) -> ground_truth_t | None:
        best = min(self.truth, key=lambda m: abs(m.utime - utime), default=None)
        return best if best is not None and abs(best.utime - utime) <= 30_000 else None


def angle_diff(a: float, b: float) -> float:
    return abs((a - b + math.pi) % (2 * math.pi) - math.pi)


@contextmanager
def flight(config_text: str, tmp_path, child_env, lcm_url, sanitized: bool, **driver) -> Iterator[Bus]:
    """The simulator on config_text and auv-frontseat (`driver`: programs.frontseat's
    port or tcp, protocol, ...) against it, the bus listening; after the block both
    stopped, the driver's stderr (it must exit clean) in tmp_path/driver.stderr."""
    config = tmp_path / "sim.yaml"
    config.write_text(config_text)
    bus = Bus(lcm_url)
    sim_out = open(tmp_path / "sim.out", "w")
    sim = subprocess.Popen(
        programs.simulator(config, lcm_url=lcm_url), stdout=sim_out, stderr=subprocess.STDOUT, env=child_env
    )
    proc = None
    try:
        # the driver once the simulator's port is there: its first attempt finds it (a
        # refused one waits up to 2 s of wall time to try again, 16 s of this flight)
        deadline = time.monotonic() + 30.0
        while "running" not in (tmp_path / "sim.out").read_text():
            assert sim.poll() is None and time.monotonic() < deadline, "the simulator did not start"
            time.sleep(0.02)
        build = c_program("bin/auv-frontseat", sanitized).parent.parent
        cmd = programs.frontseat(
            build,
            vehicle=VEHICLE,
            lcm_url=lcm_url,
            origin=ORIGIN,
            max_depth_m=40.0,
            min_speed_mps=0.5,
            max_speed_mps=2.0,
            silent_after_s=2.0,
            setpoint_timeout_s=SETPOINT_TIMEOUT_S,
            clock="sim",
            **driver,
        )
        proc = start(cmd, tmp_path, child_env)
        yield bus
    finally:
        bus.want = None
        try:
            if proc is not None:
                finish(proc, tmp_path)
        finally:
            stop(sim)
            sim_out.close()


def granted_at_depth(bus: Bus) -> frontseat_status_t:
    """Wait for control; it came at depth. The status that says so."""
    bus.wait(lambda: bus.fs and bus.fs[-1].has_control, "control granted")
    granted = bus.fs[-1]
    assert granted.state == frontseat_status_t.STATE_PAYLOAD and granted.control_granted == 1
    assert bus.truth_at(granted.utime) is None or bus.truth_at(granted.utime).eta[2] >= 1.9
    return granted


def turns_and_dives(bus: Bus) -> None:
    """The vehicle turns to the heading and reaches the depth asked (bus.want)."""

    def there() -> bool:
        t = bus.truth[-1] if bus.truth else None
        return t is not None and angle_diff(t.eta[5], math.pi / 2) < math.radians(3) and abs(t.eta[2] - 6.0) < 0.5

    bus.wait(there, "heading 90 and depth 6 m", timeout=90.0)


def nav_is_the_truth(bus: Bus, latency_s: float, position_m: float) -> None:
    """Ten NAV from the frontseat, each the truth (at its stamp less the line's
    latency_s) within the sentences' resolution."""
    n0 = len(bus.nav)
    bus.wait(lambda: len(bus.nav) >= n0 + 10, "ten NAV")
    compared = 0
    for nav in bus.nav[n0:]:
        t = bus.truth_at(nav.utime - int(latency_s * 1e6))
        if t is None:
            continue
        compared += 1
        assert math.hypot(nav.north_m - t.eta[0], nav.east_m - t.eta[1]) < position_m, (nav, t)
        assert abs(nav.depth_m - t.eta[2]) < 0.1 and angle_diff(nav.heading_rad, t.eta[5]) < math.radians(1.0)
        assert abs(nav.pitch_rad - t.eta[4]) < math.radians(1.0)
        assert nav.altitude_m > 0 and math.isnan(nav.v_mps) and math.isnan(nav.course_over_ground_rad)
    assert compared >= 5


# the sanitized build only: the unit tests cover both builds' parsing and
# bytes; this flight is the process under ASan/UBSan (8 s, the suite's budget)
@pytest.mark.parametrize("sanitized", [True], ids=["sanitized"])
def test_auv_frontseat_flies_the_simulated_iver(sanitized, lcm_url, tmp_path, child_env):
    wire = "{protocol: iver3, pty: fs0, baud: 19200}"
    text = config(wire, warp=WARP, abort_at=ABORT_AT, silent_at=SILENT_AT, silent_for=SILENT_FOR)
    with flight(text, tmp_path, child_env, lcm_url, sanitized, port=tmp_path / "fs0", baud=19200) as bus:
        # at the surface: asked, refused (its own mission: mode N), then granted at depth
        bus.wait(lambda: bus.fs and bus.fs[-1].requesting, "a request under way")
        assert not bus.fs[-1].has_control and bus.fs[-1].mode == "N"
        assert bus.truth and bus.truth[-1].eta[2] < 2.0
        assert granted_at_depth(bus).mode == "A"
        turns_and_dives(bus)
        # the frontseat's NAV is the truth within the sentences' resolution (and one
        # sentence's time on the line: its answer leaves at the step the poll arrived)
        nav_is_the_truth(bus, latency_s=0.08, position_m=0.5)  # ~150 bytes at 19200 baud

        # over the limits: clamped (depth) and refused (speed), each with its reason
        clamped0 = bus.fs[-1].setpoints_clamped
        bus.setpoint(math.pi / 2, 200.0, 1.5)
        bus.wait(lambda: bus.fs[-1].setpoints_clamped > clamped0, "a clamped setpoint")
        assert "depth over the maximum" in bus.fs[-1].last_refusal
        bus.setpoint(math.pi / 2, 6.0, 0.1)
        bus.wait(lambda: bus.reason("setpoint: speed under the minimum") >= 1, "a refused setpoint")
        # driver_status_t and frontseat_status_t are two messages: the second may come later
        bus.wait(lambda: bus.fs[-1].setpoints_refused >= 1, "the refusal in frontseat_status_t")

        # the frontseat falls silent, then answers again and gives control back
        bus.wait(lambda: bus.fs[-1].state == frontseat_status_t.STATE_SILENT, "silence", timeout=90.0)
        s = bus.fs[-1]
        assert not s.has_control and not s.requesting and s.last_message_age_s >= 2.0
        bus.wait(lambda: bus.fs[-1].has_control, "control again after the silence", timeout=60.0)

        # its operator aborts: control taken back, the abort's word reported
        bus.wait(lambda: bus.fs[-1].state == frontseat_status_t.STATE_ERROR, "the abort", timeout=90.0)
        s = bus.fs[-1]
        assert s.error and s.error_text == "Stl" and s.mode == "S" and not s.has_control
        assert s.control_lost >= 2
    assert "control granted to the payload" in (tmp_path / "driver.stderr").read_text()


BLUEFIN_ABORT_AT = 45.0


def test_auv_frontseat_flies_the_simulated_bluefin(lcm_url, tmp_path, child_env):
    """--protocol bluefin against the simulator's Bluefin on TCP (Huxley's way), the
    sanitized build only: the vehicle's $BFACK refusal at the surface, its $BFCTL
    grant at depth, the flight, NAV from $BFNVG/$BFNVR, control taken back at the abort."""
    port = free_tcp_port()
    wire = f"{{protocol: bluefin, tcp: '127.0.0.1:{port}', baud: 115200, nav_rate_hz: 5, request_timeout_s: 3}}"
    text = config(wire, warp=WARP, abort_at=BLUEFIN_ABORT_AT)
    with flight(text, tmp_path, child_env, lcm_url, True, tcp=f"127.0.0.1:{port}", protocol="bluefin") as bus:
        # at the surface: asked, and the vehicle says no ($BFACK status 1, its reason; each
        # frontseat_status_t of the second is read: driver_status_t comes at 1 Hz of wall
        # time, 8 s of this flight, and may first tell of it after the grant)
        refused = "refused by the frontseat: above the control depth"
        bus.wait(lambda: bus.fs and bus.fs[-1].last_refusal == refused, "the vehicle's refusal")
        s = bus.fs[-1]
        assert not s.has_control and s.mode == "Running" and s.protocol == "bluefin" and s.setpoints_refused >= 1
        at = bus.truth_at(s.utime)  # (the vehicle judged it at its step before: 20 ms, 1 cm)
        assert at is None or at.eta[2] < 2.05
        granted = granted_at_depth(bus)  # its $BFCTL,TIME,1
        assert granted.mode == "Running"
        turns_and_dives(bus)
        # NAV: ddmm.mmmm is some 0.19 m; the line at 115200 baud takes no time worth a bin
        nav_is_the_truth(bus, latency_s=0.0, position_m=0.5)
        sog = [n.speed_over_ground_mps for n in bus.nav[-10:]]
        t = bus.truth[-1]
        assert all(abs(v - math.hypot(t.nu[0], t.nu[1])) < 0.15 for v in sog), (sog, t.nu)

        # its operator aborts: $BFCTL 0 and $BFMIS Aborted; a request now is refused again
        bus.wait(lambda: not bus.fs[-1].has_control, "control taken back", timeout=60.0)
        bus.wait(lambda: "aborted" in bus.fs[-1].last_refusal, "a refusal after the abort")
        s = bus.fs[-1]
        assert s.mode == "Aborted" and s.control_lost == 1 and s.state == frontseat_status_t.STATE_FRONTSEAT
        assert bus.truth[-1].utime >= BLUEFIN_ABORT_AT * 1e6
        bus.wait(lambda: bus.reason("setpoint: refused by the frontseat") >= 1, "the refusals counted by reason")
    assert "control granted to the payload" in (tmp_path / "driver.stderr").read_text()

"""The fins and thruster at the wire, end to end (docs/simulator.md, "Fins and thruster
at the wire"): a running simulator whose actuators are a Maestro on a pseudo-terminal
(`actuators.wire`, the committed REMUS 100 table), the real auv-servo on that pty
(`--clock sim`), and actuators_t published on LCM. The simulated fins and propeller
(<V>.ACTUATOR_STATE) follow the command within the table's quantisation; when the
commands stop, the driver's watchdog sets neutral and the fins follow it; the
simulator's own stale report then comes, and it holds the Maestro's targets (its
`on_stale: safe` does not act at the wire)."""

from __future__ import annotations

import subprocess
from pathlib import Path

import lcm
import pytest
from conftest import c_program
from lcm_proc import pump, stop
from test_gps_driver import finish, start

from auv import actuator_state_t, actuators_t, driver_status_t, sim_clock_t
from auvlcm import programs

ROOT = Path(__file__).resolve().parents[2]
TABLE = ROOT / "missions" / "hil" / "remus100_fins.table"
VEHICLE = "AUV1"
# the table's quantum, a quarter-microsecond: 0.25 us / (1000 us/rad), 0.25 us / (0.2 us/rpm)
FIN_TOL_RAD = 0.25 / 1000.0
RPM_TOL = 0.25 / 0.2

CONFIG = """
vehicle: {{id: {vehicle}}}
simulation: {{clock: realtime, command_timeout_s: 2.0, on_stale: safe, actuator_state_rate_hz: 20}}
safe_command: {{rudder_rad: 0.1, stern_plane_rad: -0.2, prop_rpm: 300}}
initial: {{depth_m: 5.0}}
environment: {{bathymetry: "flat:depth=50", waves: {{height_m: 0.0}}}}
sensors: {{depth: {{}}}}
actuators:
  wire: {{protocol: maestro, pty: servo0, baud: 115200, table: {table}}}
"""


class Bus:
    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self.clock = 0
        self.state: list[actuator_state_t] = []
        self.status: list[driver_status_t] = []
        self.seq = 0

        def on_clock(_c, d):
            self.clock = max(self.clock, sim_clock_t.decode(d).utime)

        self.lc.subscribe("SIM.CLOCK", on_clock).set_queue_capacity(10000)
        self.lc.subscribe(
            f"{VEHICLE}.ACTUATOR_STATE", lambda c, d: self.state.append(actuator_state_t.decode(d))
        ).set_queue_capacity(10000)
        self.lc.subscribe(
            f"{VEHICLE}.DRIVER.SERVO", lambda c, d: self.status.append(driver_status_t.decode(d))
        ).set_queue_capacity(10000)

    def reason(self, name: str) -> int:
        if not self.status:
            return 0
        s = self.status[-1]
        return dict(zip(s.reason, s.reason_count)).get(name, 0)

    def command(self, rudder: float, stern: float, rpm: float) -> None:
        """An actuators_t stamped with the newest SIM.CLOCK (the driver's clock)."""
        self.seq += 1
        m = actuators_t()
        m.utime, m.vehicle, m.seq = self.clock, VEHICLE, self.seq
        m.rudder_rad, m.stern_plane_rad, m.prop_rpm = rudder, stern, rpm
        self.lc.publish(f"{VEHICLE}.ACTUATORS", m.encode())

    def wait(self, until, what: str, timeout: float = 20.0, command=None) -> None:
        """Handle messages until until(); command: published at every clock (20 Hz or so)."""

        def step() -> bool:
            if command is not None:
                self.command(*command)
            return until()

        last = self.state[-1] if self.state else None
        ok = pump(self.lc, step, timeout)
        assert ok, f"waited {timeout} s for {what}; last state {last}, last status {self.status[-1:]}"


def near(s: actuator_state_t, rudder: float, stern: float, rpm: float) -> bool:
    return (
        abs(s.rudder_rad - rudder) <= FIN_TOL_RAD
        and abs(s.stern_plane_rad - stern) <= FIN_TOL_RAD
        and abs(s.prop_rpm - rpm) <= RPM_TOL
    )


# the sanitized build only: the unit tests cover both builds' parsing and
# bytes; this flight is the process under ASan/UBSan (8 s, the suite's budget)
@pytest.mark.parametrize("sanitized", [True], ids=["sanitized"])
def test_auv_servo_drives_the_simulated_fins(sanitized, lcm_url, tmp_path, child_env):
    config = tmp_path / "sim.yaml"
    config.write_text(CONFIG.format(vehicle=VEHICLE, table=TABLE))
    bus = Bus(lcm_url)
    sim_out = open(tmp_path / "sim.out", "w")
    sim = subprocess.Popen(
        programs.simulator(config, lcm_url=lcm_url), stdout=sim_out, stderr=subprocess.STDOUT, env=child_env
    )
    build = c_program("bin/auv-servo", sanitized).parent.parent
    cmd = programs.device_driver(
        build,
        "servo",
        vehicle=VEHICLE,
        lcm_url=lcm_url,
        port=tmp_path / "servo0",
        baud=115200,
        clock="sim",
        extra=programs.servo_table_flags(TABLE),
    )
    driver = start(cmd, tmp_path, child_env)
    try:
        bus.wait(lambda: bus.status and bus.status[-1].port_open and bus.clock > 0, "the port open, a clock")
        # the driver's neutral at the start is a target command on the wire
        bus.wait(lambda: bus.state and bus.state[-1].last_command_utime > 0, "the first target command")

        # a command, kept fresh: the fins and the propeller follow within a quantum
        want = (0.1234, -0.1501, 1234.5)
        bus.wait(lambda: bus.state and near(bus.state[-1], *want), "the commanded fins", command=want)
        s = bus.state[-1]
        assert not s.command_stale and s.last_command_utime > 0
        assert bus.reason("watchdog timeout") == 0

        # silence: the driver's watchdog sets neutral, and the simulated fins follow it
        bus.wait(lambda: bus.reason("watchdog timeout") == 1, "the driver's watchdog")
        bus.wait(lambda: near(bus.state[-1], 0.0, 0.0, 0.0), "neutral on the fins")
        # the simulator's stale report comes later; it holds the Maestro's neutral, not its safe command
        bus.wait(lambda: bus.state[-1].command_stale, "the simulator's stale report")
        n = len(bus.state)
        pump(bus.lc, lambda: len(bus.state) >= n + 10, 5.0)
        assert all(near(x, 0.0, 0.0, 0.0) and x.command_stale for x in bus.state[n:])

        # commands again: the fins follow again, fresh
        want = (-0.2, 0.05, -600.0)
        bus.wait(lambda: near(bus.state[-1], *want) and not bus.state[-1].command_stale, "resumed", command=want)
    finally:
        text = finish(driver, tmp_path)
        rc = stop(sim)
        sim_out.close()
    out = (tmp_path / "sim.out").read_text()
    assert rc == 0, out
    assert "actuators maestro on pty" in out and "the Maestro holds its targets" in out, out
    assert "dropped: watchdog timeout" in text

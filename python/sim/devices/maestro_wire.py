"""The fins and thruster at the wire: the Maestro emulator on a port, driving the actuators.

`actuators: {wire: {protocol: maestro, pty: ..., table: FILE}}` (docs/simulator.md,
"Fins and thruster at the wire"). The vehicle's auv-servo writes Maestro commands on
the port; this emulator feeds them to sim.devices.maestro.Maestro (I/O-free), sends
its replies (Get Position, Get Moving State, Get Errors) back on the same line, and
turns the channels' pulses into the command the actuator model follows, through the
inverse of the channel table both sides read (ChannelTable.command).

Time: the Maestro ramps (its speed and acceleration, in 10 ms updates) in sim time;
command_at(t) lets it run to t and reads the pulses, once per physics step. The
pulses are what a servo would be sent, so the actuator model's own limits (fin slew,
the propeller's lag) still apply after them, as the servos' and the motor's.

Fresh commands: a real Maestro holds its last targets however long the host is
silent; neutral on silence is the driver's watchdog (auv-servo), which the Maestro
sees as one more Set Target. `last_command_t` is the sim time of the newest target
command obeyed, for the simulator's stale report; nothing here ever goes to neutral
on its own (the Maestro's own serial timeout and its "on error" positions are
device settings this emulator does not model).
"""

from __future__ import annotations

from dataclasses import dataclass

from confcheck import setting
from sim.actuators import Command
from sim.devices.emulator import DeviceContext, Emulator
from sim.devices.maestro import ChannelTable


@dataclass
class MaestroOptions:
    # the channel table (required): the file auv-servo reads with --table, relative to
    # the configuration's folder (c/drivers/servo/am_config.c, sim.devices.maestro.parse_table)
    table: str = ""
    channels: int = setting(24, one_of=(6, 12, 18, 24))  # the Maestro model's channel count
    # an input device's LCM beside the bytes: true, the simulator also takes <V>.ACTUATORS
    # (the newer of the two commands acts); false, the Maestro's pulses alone
    take_lcm: bool = False


class MaestroWire(Emulator):
    sensor = "actuators"  # the simulator's part it belongs to (not a sensor: Devices.add)
    protocol = "maestro"
    Options = MaestroOptions
    options: MaestroOptions

    @classmethod
    def problems(cls, options: MaestroOptions) -> dict[str, str]:
        if not options.table:
            return {"table": "the channel table is required: table: FILE (the file auv-servo reads)"}
        return {}

    def __init__(self, ctx: DeviceContext, table: ChannelTable) -> None:
        super().__init__(ctx)
        self.table = table
        self.maestro = table.maestro(self.options.channels)
        self._t = 0.0  # the sim time the Maestro's ramps have run to
        self._seen_commands = 0
        self.last_command_t: float | None = None  # sim time of the newest target command obeyed

    def encode(self, msg, truth) -> list[bytes]:
        return []  # no measurement: it speaks when spoken to

    def _run_to(self, t: float) -> None:
        if t > self._t:
            self.maestro.advance(t - self._t)
            self._t = t

    def receive(self, data: bytes, t: float) -> None:
        """The driver's bytes at the step t: obeyed in order, replies sent at once."""
        self._run_to(t)
        reply = self.maestro.feed(data)
        if reply:
            self.send(reply, t)
        if self.maestro.target_commands != self._seen_commands:
            self._seen_commands = self.maestro.target_commands
            self.last_command_t = t

    def command_at(self, t: float) -> Command:
        """What the channels' pulses command at sim time t (ramps run up to t)."""
        self._run_to(t)
        return self.table.command(self.maestro.positions())

"""The hardware-in-the-loop process: physics, sensors and actuators over LCM.

One process per vehicle. It publishes each sensor on <VEHICLE>.<TOPIC> at
that sensor's rate, ground truth on <VEHICLE>.TRUTH, what the actuators do on
<VEHICLE>.ACTUATOR_STATE, its health on <VEHICLE>.HEALTH, and (when it runs
the world alone in real-time or scaled mode) the global clock on SIM.CLOCK.
It consumes <VEHICLE>.ACTUATORS and, in lockstep, SIM.CLOCK; with the fins and
thruster at the wire (`actuators: {wire: ...}`), the commands are a Maestro's
channel pulses on a port instead (sim.devices.maestro_wire), and
<VEHICLE>.ACTUATORS only if its `take_lcm` says so; with a frontseat (`frontseat:`,
sim.frontseat), the frontseat's own loops command them and <VEHICLE>.ACTUATORS is not
taken.

Time stamps follow the project's rule (auvlcm.timepolicy, docs/simulator.md):
a SIM.CLOCK that goes back, jumps unconfirmed or is out of range is dropped;
a command stamped outside the valid range, more than the tolerance ahead of
the simulator's clock, or older than the last one applied is dropped. Drops
are counted per reason (the summary line) and logged the first time.
"""

from __future__ import annotations

import math
import os
import select
import signal
import time
from typing import Callable

import lcm

from auv import actuator_state_t, actuators_t, ground_truth_t, process_health_t, sim_clock_t
from auvlcm.rx import Receiver
from auvlcm.sender import ThreadedLcm, open_lcm
from auvlcm.timepolicy import ClockGate, InputGate, TimeDrops
from auvlcm.url import check_local, default_url
from sim import clock_modes
from sim.actuators import Command
from sim.clock import ClockSource
from sim.clock_modes import LOCKSTEP
from sim.config import SimConfig
from sim.devices.device import build_devices
from sim.devices.emulator import DeviceContext
from sim.devices.maestro_wire import MaestroWire
from sim.environment import Environment
from sim.model import Truth, VehicleModel
from sim.modem.node import make_modem, wire_modem
from sim.periodic import Periodic
from sim.sensors import FITTED_UNLESS_LISTED, REGISTRY
from sim.sensors.base import utime
from sim.wire import Encoder


def build_sensors(cfg: SimConfig, model: VehicleModel) -> list:
    """Every enabled sensor of the configuration (if none are listed, all those
    fitted unless listed: sim.sensors.FITTED_UNLESS_LISTED),
    each given the parts of the world it declares it uses (Sensor.uses)."""
    out = []
    world = {"env": model.env, "frame": model.frame}
    names = cfg.sensors or {name: REGISTRY[name][0]() for name in FITTED_UNLESS_LISTED}
    for name, scfg in names.items():
        if not scfg.enabled or getattr(scfg, "channel", "") == "off":
            continue
        cls = REGISTRY[name][1]
        out.append(cls(scfg, cfg.sim.seed, cfg.vehicle_id, **{part: world[part] for part in cls.uses}))
    return out


def build_extras(cfg: SimConfig, sensors: list, publish_world: bool, devices, pacer) -> list:
    """Outputs beyond the instruments: the sidescan sonar, the reacquire-identify
    sensor and the time link, when configured (the first two at the wire too, the
    time link only there: their ports join devices)."""
    out: list = []
    if cfg.sonar is not None:
        from sim.sonar.publisher import SonarOutputs

        out.append(SonarOutputs(cfg, sensors, publish_world, devices))
    if getattr(cfg, "identify", None) is not None:
        from sim.sonar.identify import IdentifyOutputs

        out.append(IdentifyOutputs(cfg, sensors, devices))
    if getattr(cfg, "time_link", None) is not None:
        from sim.time_link import TimeLinkOutputs

        out.append(TimeLinkOutputs(cfg.time_link, devices, cfg.vehicle_id, cfg.sim.seed, pacer))
    return out


def build_model(cfg: SimConfig) -> VehicleModel:
    env = Environment(cfg.env, cfg.path.parent)
    model = VehicleModel(cfg.vehicle, env, 1.0 / cfg.sim.physics_rate_hz)
    i = cfg.initial
    model.set_pose(
        (i.north_m, i.east_m, i.depth_m, i.roll_rad, i.pitch_rad, i.heading_rad),
        (i.speed_mps, 0.0, 0.0, 0.0, 0.0, 0.0),
        rpm=i.prop_rpm,
    )
    model.command = Command(0.0, 0.0, i.prop_rpm)
    return model


class Simulator:
    def __init__(self, cfg: SimConfig, fast: bool = False, lc: lcm.LCM | None = None) -> None:
        from sim.clock import Pacer

        self.cfg = cfg
        self.vid = cfg.vehicle_id
        self.model = build_model(cfg)
        self.sensors = build_sensors(cfg, self.model)
        self.truth = Truth()
        s = cfg.sim
        self.dt = self.model.dt
        self.pacer = Pacer(s.clock, s.warp, self.dt, fast=fast)
        self.publish_clock = s.publish_clock == "yes" or (s.publish_clock == "auto" and s.clock != LOCKSTEP)
        self.publish_clock &= not cfg.multihil.enabled  # the world's server does it
        url = check_local(s.lcm_url or default_url())
        # The sender thread serves a loop that runs as fast as it can (fast,
        # stepped): a loop paced by the wall clock has the time to publish,
        # and its multi-HIL clock sync wants no queue between it and the wire.
        self.lc = lc or open_lcm(
            url,
            s.publish_thread and (fast or s.clock == LOCKSTEP),
            lambda line: print(f"sim: {self.vid}: {line}", flush=True),
        )
        # publish() of the instance itself, looked up once: through a wrapper's
        # __getattr__ (auvlcm.chanfilter.FilteredLcm) it costs a Python call each time
        self.publish_raw: Callable[[str, bytes], None] = self.lc.publish
        # a sender thread's flush(): called before the loop waits (see _drain)
        self._flush = getattr(self.lc, "flush", None)
        self.rx = Receiver(self.lc)
        self.time_drops = TimeDrops(f"sim: {self.vid}", lambda line: print(line, flush=True))
        self.clock_gate = ClockGate(self.time_drops)  # stepped: the SIM.CLOCK followed
        self._cmd_gate = InputGate(self.time_drops, f"{self.vid}.ACTUATORS")
        # where a command that passed the checks goes, if not applied at once
        self._command_filter: Callable[[str, actuators_t], None] | None = None
        wire = cfg.actuators.wire
        # a frontseat (sim.frontseat) commands the fins and the propeller itself
        if cfg.frontseat is None and (wire is None or wire.options.take_lcm):
            self.rx.subscribe(f"{self.vid}.ACTUATORS", actuators_t, self._on_actuators, queue_capacity=200)
        if s.clock == LOCKSTEP and not cfg.multihil.enabled:  # multi-HIL: the node's clock
            self.rx.subscribe("SIM.CLOCK", sim_clock_t, self._on_clock, queue_capacity=1000)
        self.modem = make_modem(cfg, self.model.env, self.rx, self._publish, self.time_drops, self.clock_now_us)
        self._fd = self.lc.fileno()
        poller = select.poll()
        poller.register(self._fd, select.POLLIN)
        self._poll = poller.poll
        self.last_cmd_t: float | None = None  # sim time a command was applied
        self.last_cmd_utime = 0
        self.stale = False
        self.stale_events = 0
        self.rejected_commands = 0
        self.missed_commands = 0  # gaps in actuators_t.seq
        self._last_seq: int | None = None
        self.published = 0
        self.stop_requested = False
        self._clock_started = False
        # the simulator's own periodic outputs
        self._truth_every = Periodic(1.0 / s.truth_rate_hz)
        self._act_every = Periodic(1.0 / s.actuator_state_rate_hz)
        self._clock_every = Periodic(1.0 / s.clock_rate_hz)
        self._health_every = Periodic(s.health_period_s, s.health_period_s)
        self._next_due = 0.0  # earliest of every output's next time
        self._sensor_channels = [(sen, f"{self.vid}.{sen.topic}") for sen in self.sensors]
        # what _outputs() calls per sensor: when it is due next, its poll as bytes
        # (or None), its channel
        # sensors at the wire (docs/simulator.md, "Devices at the wire"): their lines follow
        # the steps where the wall clock does not pace them
        stepped = s.clock == LOCKSTEP or self.pacer.fast or cfg.multihil.enabled
        self.devices = build_devices(self.sensors, self.vid, s.seed, self.model.frame, self.pacer, stepped)
        wire_modem(self.modem, self.devices, self.vid, s.seed)  # the modem at the wire, on the same lines' clock
        self._sensor_polls = [(sen.next_due, self.devices.poll_for(sen), ch) for sen, ch in self._sensor_channels]
        # the fins and thruster at the wire: a Maestro's pulses are the commands
        self.servo: MaestroWire | None = None
        self._servo_seen: float | None = None  # sim time of the Maestro's newest target command taken
        self._wire_acts = False  # its pulses command the actuators (not the initial or an LCM command)
        if wire is not None:
            assert cfg.actuators.table is not None  # read with the configuration
            ctx = DeviceContext(self.vid, "actuators", s.seed, wire.options, self.model.frame)
            self.servo = MaestroWire(ctx, cfg.actuators.table)
            try:
                self.devices.add(self.servo, wire)
            except BaseException:
                self.devices.close()
                raise
        # a commercial vehicle's frontseat: its own loops fly the vehicle (docs/frontseat.md)
        self.frontseat = None
        if cfg.frontseat is not None:
            from sim.frontseat import FrontseatVehicle

            try:
                self.frontseat = FrontseatVehicle(cfg.frontseat, self.devices, self.vid, s.seed, self.model)
            except BaseException:
                self.devices.close()
                raise
        # other outputs polled like sensors: next_due(), poll(truth) -> [(channel, bytes)]
        try:
            self.extras = build_extras(cfg, self.sensors, self.publish_clock, self.devices, self.pacer)
        except BaseException:
            self.devices.close()  # the ports opened so far: their links and threads
            raise
        self._ch_truth, self._ch_act = f"{self.vid}.TRUTH", f"{self.vid}.ACTUATOR_STATE"
        self._ch_health = f"{self.vid}.HEALTH"
        self._enc_truth = Encoder(ground_truth_t, vehicle=self.vid)
        self._enc_act = Encoder(actuator_state_t, vehicle=self.vid)
        self._enc_clock = Encoder(sim_clock_t, server_id=cfg.multihil.client_id)
        self._enc_health = Encoder(process_health_t, vehicle=self.vid, process="sim")
        self._step_us = utime(self.dt)
        self._cpu0 = os.times()
        self._wall_health = time.monotonic()
        self.mh = None  # multi-HIL: shared world, global clock (docs/multihil.md)
        self.follow = None  # stepped on its own: a participant when the clock is lockstep
        if cfg.multihil.enabled:
            from sim.multihil.hook import SimHook

            self.mh = SimHook(self)
        elif s.clock == LOCKSTEP:
            from sim.lockstep_follow import LockstepFollower

            self.follow = LockstepFollower(self)

    # ------------------------------------------------------------ handlers
    def clock_now_us(self) -> int | float | None:
        """The global time this simulator judges stamps against (None: it has none yet):
        the SIM.CLOCK it follows (stepped), the world's clock (multi-HIL), else its own."""
        if self.mh is not None:
            return self.mh.node.global_now_us()  # lockstep: its last accepted SIM.CLOCK
        if self.cfg.sim.clock == LOCKSTEP:
            return self.clock_gate.now
        return utime(self.model.t)

    def _on_actuators(self, _channel: str, msg) -> None:
        vals = (msg.rudder_rad, msg.stern_plane_rad, msg.prop_rpm)
        if msg.vehicle != self.vid or not all(math.isfinite(v) for v in vals):
            self.rejected_commands += 1
            return
        if not self._cmd_gate.offer(msg.utime, self.clock_now_us()):
            return
        if self._command_filter is not None:
            self._command_filter(_channel, msg)
        else:
            self.apply_command(_channel, msg)

    def apply_command(self, _channel: str, msg) -> None:
        """Act on a command that passed the checks (a command filter calls this when
        the command's time comes)."""
        vals = (msg.rudder_rad, msg.stern_plane_rad, msg.prop_rpm)
        if self._last_seq is not None and msg.seq > self._last_seq + 1:
            self.missed_commands += msg.seq - self._last_seq - 1
        self._last_seq = msg.seq  # a pilot restart (seq going back) just resyncs
        self.model.command = Command(*vals)
        self._commanded(msg.utime)
        self._wire_acts = False  # the LCM command is the newer: it acts until the wire's next

    def _commanded(self, utime_us: int) -> None:
        self.last_cmd_t = self.model.t
        self.last_cmd_utime = utime_us
        if self.stale:
            self.stale = False
            print(f"sim: {self.vid}: commands resumed at t={self.model.t:.2f}s", flush=True)

    def _servo_command(self) -> None:
        """Before each physics step: the Maestro's pulses, ramped to now, command the
        actuators once its host has sent a target (until then the initial command, as
        before a first LCM command); with take_lcm, until an LCM command is the newer.
        Its newest target command is a fresh command: it stamps last_command_utime
        (sim time: the driver's actuators_t stamp does not cross the wire)."""
        servo = self.servo
        assert servo is not None
        newest = servo.last_command_t
        if newest is not None and newest != self._servo_seen:
            self._servo_seen = newest
            self._wire_acts = True
            self._commanded(utime(newest))
        if self._wire_acts:
            self.model.command = servo.command_at(self.model.t)

    # --------------------------------------------------- extension points
    # What a part plugged into the simulator (sim.lockstep_follow, the
    # multi-HIL hook) may change, besides follow_clock() and join_at().
    def set_command_filter(self, hold: Callable[[str, actuators_t], None]) -> None:
        """Pass every command that passed the checks to hold instead of applying it;
        hold calls apply_command() when it decides (lockstep: at the command's
        time stamp). One filter: a second one would silently bypass the first."""
        if self._command_filter is not None:
            raise RuntimeError(f"sim: {self.vid}: a command filter is set already")
        self._command_filter = hold

    def set_clock_source(self, source: ClockSource) -> None:
        """Pace the free-running steps by source's global time (sim.clock.Pacer)."""
        self.pacer.set_clock_source(source)

    def replace_world(self, env: Environment) -> None:
        """Run in env's world from the next step on (sim.model.VehicleModel.replace_world)."""
        self.model.replace_world(env)

    @property
    def clock_started(self) -> bool:
        """Whether the simulator joined the global clock (join_at): before, a stepped
        or multi-HIL simulator has no time of the world's."""
        return self._clock_started

    def _on_clock(self, _channel: str, msg) -> None:
        if self.clock_gate.offer(msg.utime, msg.term):
            self.follow_clock(msg.utime)
            if self.follow is not None:
                self.follow.on_clock(msg)

    def follow_clock(self, utime_us: int) -> None:
        """Stepped: advance up to this (accepted) global time, joining the world at the first."""
        t = utime_us / 1e6
        if not self._clock_started:
            self.join_at(t)
        self.pacer.target_t = t

    def join_at(self, t: float) -> None:
        """Join the world at its current time instead of replaying from 0."""
        self._clock_started = True
        self.model.dyn.t = t
        self.last_cmd_t = None
        for every in (self._truth_every, self._act_every, self._clock_every):
            every.restart(t)
        self._health_every.restart(t + self._health_every.period)
        self._next_due = t
        for sen in self.sensors:
            sen.restart(t)
        for extra in self.extras:
            extra.restart(t)
        self._t_start = t
        if not self._cmd_gate.judge_held(utime(t)):  # a command from before the clock
            self.model.command = Command(0.0, 0.0, self.cfg.initial.prop_rpm)
            self.last_cmd_utime = 0
        self._outputs()

    # -------------------------------------------------------------- output
    def _publish(self, channel: str, data: bytes) -> None:
        self.publish_raw(channel, data)
        self.published += 1

    def _check_stale(self) -> None:
        t = self.model.t
        since = t - (self.last_cmd_t if self.last_cmd_t is not None else self._t_start)
        if not self.stale and since > self.cfg.sim.command_timeout_s:
            self.stale = True
            self.stale_events += 1
            if self.servo is not None:
                # a Maestro holds its targets whatever the host does: neutral on silence
                # is the driver's watchdog, on the wire; the stale flag only reports
                print(
                    f"sim: {self.vid}: no target command on the Maestro's wire for {since:.2f}s at "
                    f"t={t:.2f}s: the Maestro holds its targets",
                    flush=True,
                )
                return
            if self.cfg.sim.on_stale == "safe":
                self.model.command = Command(
                    self.cfg.safe_command.rudder_rad,
                    self.cfg.safe_command.stern_plane_rad,
                    self.cfg.safe_command.prop_rpm,
                )
            print(
                f"sim: {self.vid}: no actuator command for {since:.2f}s at t={t:.2f}s: "
                f"{'safe command' if self.cfg.sim.on_stale == 'safe' else 'holding last command'}",
                flush=True,
            )

    def _outputs(self) -> None:
        """Publish whatever is due at the current sim time.

        Most physics steps have nothing due (50 Hz physics, sensors at 20 Hz
        and less): those cost one comparison, and the truth snapshot is only
        taken when something will read it.
        """
        t = self.model.t
        if self.modem is not None:  # every step: a frame may arrive at any step
            self.modem.step(t, tuple(self.model.dyn.x[0:3]))
        if self.devices:  # every step: the lines' step clock, what the far ends wrote
            self.devices.step(t)
        if t < self._next_due - 1e-9:
            return
        tr = self.model.truth(self.truth)
        publish = self._publish
        sensors_due = math.inf
        for next_due, poll, channel in self._sensor_polls:
            if t >= next_due() - 1e-9:  # what poll() itself checks first: skip the call
                data = poll(tr)
                if data is not None:
                    publish(channel, data)
            due = next_due()
            if due < sensors_due:
                sensors_due = due
        for extra in self.extras:
            for channel, data in extra.poll(tr):
                publish(channel, data)
        truth, act, clock, health = (self._truth_every, self._act_every, self._clock_every, self._health_every)
        if truth.due(t):
            truth.advance(t)
            publish(
                self._ch_truth,
                self._enc_truth.pack(
                    utime(tr.t),
                    *tr.eta,
                    *tr.nu,
                    *tr.nu_dot,
                    *tr.current_ned,
                    tr.altitude_m,
                    tr.water_depth_m,
                    tr.latitude_deg,
                    tr.longitude_deg,
                ),
            )
        if act.due(t):
            act.advance(t)
            a = self.model.act
            publish(
                self._ch_act,
                self._enc_act.pack(
                    utime(t), a.rudder, a.stern, a.rpm, a.thrust, a.torque, self.stale, self.last_cmd_utime
                ),
            )
        if self.publish_clock and clock.due(t):
            clock.advance(t)
            publish(
                "SIM.CLOCK",
                self._enc_clock.pack(
                    utime(t),
                    0,
                    clock_modes.WIRE[self.cfg.sim.clock],
                    self.pacer.warp if not self.pacer.fast else 0.0,
                    0,
                    self._step_us,
                ),
            )
        if health.due(t):
            health.advance(t)
            self._health()
        self._next_due = min(
            sensors_due,
            min((x.next_due() for x in self.extras), default=math.inf),
            truth.next_t,
            act.next_t,
            clock.next_t if self.publish_clock else math.inf,
            health.next_t,
        )

    def _health(self) -> None:
        """process_health_t every health_period_s of sim time (like every other output).

        queue_overflows counts actuator commands we never saw: gaps in the
        pilot's actuators_t.seq (lost on the network or in LCM's bounded
        receive queue; liblcm itself does not expose its drops).
        """
        now = time.monotonic()
        cpu = os.times()
        wall = now - self._wall_health
        load = ((cpu.user + cpu.system) - (self._cpu0.user + self._cpu0.system)) / wall if wall > 0 else 0.0
        self._cpu0, self._wall_health = cpu, now
        self._publish(
            self._ch_health,
            self._enc_health.pack(
                utime(self.model.t),
                os.getpid(),
                self.messages_received(),
                self.decode_errors(),
                self.missed_commands,
                load,
            ),
        )
        if isinstance(self.lc, ThreadedLcm):  # sends fail on the sender thread: say so here
            line = self.lc.new_errors()
            if line:
                print(f"sim: {self.vid}: {line}", flush=True)

    def decode_errors(self) -> int:
        """Undecodable messages on every subscription of the process, the node's included."""
        return self.rx.decode_errors + (self.mh.node.rx.decode_errors if self.mh is not None else 0)

    def messages_received(self) -> int:
        rxs = (self.rx, self.mh.node.rx) if self.mh is not None else (self.rx,)
        return sum(s.stats.received for rx in rxs for s in rx.subscriptions)

    # ---------------------------------------------------------------- loop
    def _drain(self, timeout_s: float) -> None:
        """Handle what LCM has for us, waiting up to timeout_s for the first message.

        Before waiting, every message published so far goes out: whoever we
        wait for (the global clock, the pilot, the lockstep server) may be
        waiting for them. The check with no wait, once per physics step, is a
        poll() on a registered descriptor: the cheapest system call for it.
        """
        if timeout_s > 0.0:
            if self._flush is not None:
                self._flush()
            ready = self._wait(timeout_s)
        else:
            ready = self._poll(0)
        while ready:
            self.lc.handle()
            ready = self._poll(0)

    def _wait(self, timeout_s: float) -> bool:
        """Block until LCM has a message or timeout_s passed (select: microsecond timeouts)."""
        return bool(select.select([self._fd], [], [], timeout_s)[0])

    def close(self) -> None:
        """Let go of LCM: stop the sender thread, drop the subscriptions.

        A process running one simulator needs none of this (its exit does
        it). An in-process user running several (the benchmark, tests) does:
        liblcm holds the handlers where Python's collector cannot see them,
        so a simulator never closed keeps its LCM instance alive, and with it
        a receive thread that every later packet still wakes.
        """
        self._close_sender()
        self._close_devices()
        for rx in (self.rx, self.mh.node.rx) if self.mh is not None else (self.rx,):
            for sub in list(rx.subscriptions):
                rx.unsubscribe(sub)

    def _close_devices(self) -> None:
        for line in self.devices.close():
            print(f"sim: {self.vid}: {line}", flush=True)
        self.devices.items.clear()

    def _close_sender(self) -> str:
        """Send what is queued and stop the sender thread; its figures for the summary."""
        if not isinstance(self.lc, ThreadedLcm):
            return ""
        self.lc.close()
        return ", " + self.lc.summary()

    def run(self) -> int:
        cfg = self.cfg
        self._t_start = self.model.t
        # stop cleanly on SIGINT/SIGTERM; the previous handlers come back at the end
        previous = {
            sig: signal.signal(sig, lambda *_: setattr(self, "stop_requested", True))
            for sig in (signal.SIGINT, signal.SIGTERM)
        }
        duration = cfg.sim.duration_s
        print(
            f"sim: {self.vid} running: clock={cfg.sim.clock} warp={self.pacer.warp:g}"
            f"{' (fast)' if self.pacer.fast else ''} physics={cfg.sim.physics_rate_hz:g}Hz "
            f"sensors={','.join(s.name for s in self.sensors)} "
            f"publish_clock={'yes' if self.publish_clock else 'no'}",
            flush=True,
        )
        # the pacer first: the lines' wall clock (sim.devices.clocks) reads it, and the
        # first outputs' bytes would otherwise wait out the time since it was made
        self.pacer.restart(self.model.t)
        if cfg.sim.clock != LOCKSTEP and self.mh is None:
            self._outputs()  # stepped, multi-HIL: nothing until the global clock says when
        wall_start = time.monotonic()
        steps0 = self.model.steps
        model, pacer, monotonic, poll = self.model, self.pacer, time.monotonic, self._poll
        duration = duration if duration > 0 else math.inf
        while not self.stop_requested:
            if self.mh is not None:
                self.mh.poll()
            elif self.follow is not None:
                self.follow.poll()
            # _t_start moves when a stepped run joins the global clock
            if model.t - self._t_start >= duration - 1e-9:
                break
            now = monotonic()
            if pacer.may_step(model.t, now):
                if poll(0):  # anything from LCM (one poll() per step)
                    self._drain(0.0)
                if self.servo is not None:
                    self._servo_command()
                if self.frontseat is not None:
                    self.model.command = self.frontseat.command(self.model)
                    self.last_cmd_t, self.last_cmd_utime = model.t, utime(model.t)  # never stale
                self._check_stale()
                model.step()
                self._outputs()
            else:
                self._drain(min(pacer.wait_s(model.t, now), 0.1))
        if self.mh is not None:
            self.mh.close()
        elif self.follow is not None:
            self.follow.close()
        sender = self._close_sender()
        for sig, handler in previous.items():
            if handler is not None:  # None: not set from Python, nothing to restore
                signal.signal(sig, handler)
        wall = time.monotonic() - wall_start
        steps = self.model.steps - steps0
        print(
            f"sim: {self.vid} stopped at t={self.model.t:.2f}s after {steps} steps in "
            f"{wall:.2f}s wall ({steps * self.dt / wall if wall > 0 else 0:.1f}x real time), "
            f"{self.published} messages published, {self.decode_errors()} decode errors, "
            f"{self.rejected_commands} commands rejected, {self.stale_events} stale events, "
            f"{self.time_drops.summary()}{sender}",
            flush=True,
        )
        if self.modem is not None:
            print(self.modem.summary(), flush=True)
        self._close_devices()
        return 0

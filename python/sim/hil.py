"""The hardware-in-the-loop process: physics, sensors and actuators over LCM.

One process per vehicle. It publishes each sensor on <VEHICLE>.<TOPIC> at
that sensor's rate, ground truth on <VEHICLE>.TRUTH, what the actuators do on
<VEHICLE>.ACTUATOR_STATE, its health on <VEHICLE>.HEALTH, and (when it runs
the world alone in real-time or scaled mode) the global clock on SIM.CLOCK.
It consumes <VEHICLE>.ACTUATORS and, in stepped mode, SIM.CLOCK.
"""

from __future__ import annotations

import math
import os
import select
import signal
import sys
import time

import lcm
from auv import actuator_state_t, actuators_t, ground_truth_t, process_health_t, sim_clock_t

from auvlcm.rx import Receiver
from auvlcm.url import check_local, default_url
from sim.actuators import Command
from sim.config import SimConfig
from sim.environment import Environment
from sim.model import Truth, VehicleModel
from sim.sensors import REGISTRY
from sim.sensors.base import utime

CLOCK_MODE = {"realtime": sim_clock_t.MODE_REALTIME, "scaled": sim_clock_t.MODE_SCALED,
              "stepped": sim_clock_t.MODE_LOCKSTEP}


def build_sensors(cfg: SimConfig, model: VehicleModel) -> list:
    """Every enabled sensor of the configuration (all of them if none are listed)."""
    out = []
    names = cfg.sensors or {name: REGISTRY[name][0]() for name in REGISTRY}
    for name, scfg in names.items():
        if not scfg.enabled:
            continue
        cls = REGISTRY[name][1]
        if name in ("gps", "ins"):
            out.append(cls(scfg, cfg.sim.seed, cfg.vehicle_id, model.frame))
        elif name == "lbl":
            out.append(cls(scfg, cfg.sim.seed, cfg.vehicle_id, model.env))
        else:
            out.append(cls(scfg, cfg.sim.seed, cfg.vehicle_id))
    return out


def build_model(cfg: SimConfig) -> VehicleModel:
    env = Environment(cfg.env, cfg.path.parent)
    model = VehicleModel(cfg.vehicle, env, 1.0 / cfg.sim.physics_rate_hz)
    i = cfg.initial
    model.set_pose((i.north_m, i.east_m, i.depth_m, i.roll_rad, i.pitch_rad, i.heading_rad),
                   (i.speed_mps, 0.0, 0.0, 0.0, 0.0, 0.0), rpm=i.prop_rpm)
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
        self.publish_clock = (s.publish_clock == "yes"
                              or (s.publish_clock == "auto" and s.clock != "stepped"))
        url = check_local(s.lcm_url or default_url())
        self.lc = lc or lcm.LCM(url)
        self.rx = Receiver(self.lc)
        self.rx.subscribe(f"{self.vid}.ACTUATORS", actuators_t, self._on_actuators,
                          queue_capacity=200)
        if s.clock == "stepped":
            self.rx.subscribe("SIM.CLOCK", sim_clock_t, self._on_clock, queue_capacity=1000)
        self.last_cmd_t: float | None = None     # sim time a command was applied
        self.last_cmd_utime = 0
        self.stale = False
        self.stale_events = 0
        self.rejected_commands = 0
        self.published = 0
        self.stop_requested = False
        self._clock_started = False
        self._next = {"truth": 0.0, "act": 0.0, "clock": 0.0}
        self._periods = {"truth": 1.0 / s.truth_rate_hz, "act": 1.0 / s.actuator_state_rate_hz,
                         "clock": 1.0 / s.clock_rate_hz}
        self._cpu0 = os.times()
        self._wall_health = time.monotonic()
        self.mh = None      # multi-HIL: shared world, global clock (docs/multihil.md)
        if cfg.multihil.enabled:
            from sim.multihil.hook import SimHook
            self.mh = SimHook(self)

    # ------------------------------------------------------------ handlers
    def _on_actuators(self, _channel: str, msg) -> None:
        vals = (msg.rudder_rad, msg.stern_plane_rad, msg.prop_rpm)
        if msg.vehicle != self.vid or not all(math.isfinite(v) for v in vals):
            self.rejected_commands += 1
            return
        self.model.command = Command(*vals)
        self.last_cmd_t = self.model.t
        self.last_cmd_utime = msg.utime
        if self.stale:
            self.stale = False
            print(f"sim: {self.vid}: commands resumed at t={self.model.t:.2f}s", flush=True)

    def _on_clock(self, _channel: str, msg) -> None:
        t = msg.utime / 1e6
        if not self._clock_started:
            self.join_at(t)
        self.pacer.target_t = t

    def join_at(self, t: float) -> None:
        """Join the world at its current time instead of replaying from 0."""
        self._clock_started = True
        self.model.dyn.t = t
        self.last_cmd_t = None
        self._next = {k: t for k in self._next}
        for sen in self.sensors:
            sen.next_t = t + sen.cfg.phase_s
        self._t_start = t
        self._outputs()

    # -------------------------------------------------------------- output
    def _publish(self, channel: str, msg) -> None:
        self.lc.publish(channel, msg.encode())
        self.published += 1

    def _check_stale(self) -> None:
        t = self.model.t
        since = t - (self.last_cmd_t if self.last_cmd_t is not None else self._t_start)
        if not self.stale and since > self.cfg.sim.command_timeout_s:
            self.stale = True
            self.stale_events += 1
            if self.cfg.sim.on_stale == "safe":
                self.model.command = Command(self.cfg.safe_command.rudder_rad,
                                             self.cfg.safe_command.stern_plane_rad,
                                             self.cfg.safe_command.prop_rpm)
            print(f"sim: {self.vid}: no actuator command for {since:.2f}s at t={t:.2f}s: "
                  f"{'safe command' if self.cfg.sim.on_stale == 'safe' else 'holding last command'}",
                  flush=True)

    def _outputs(self) -> None:
        t = self.model.t
        tr = self.model.truth(self.truth)
        vid = self.vid
        for sen in self.sensors:
            msg = sen.poll(tr)
            if msg is not None:
                self._publish(f"{vid}.{sen.topic}", msg)
        nx, per = self._next, self._periods
        if t >= nx["truth"] - 1e-9:
            nx["truth"] += per["truth"] * max(1, math.floor((t - nx["truth"]) / per["truth"]) + 1)
            self._publish(f"{vid}.TRUTH", self._truth_msg(tr))
        if t >= nx["act"] - 1e-9:
            nx["act"] += per["act"] * max(1, math.floor((t - nx["act"]) / per["act"]) + 1)
            self._publish(f"{vid}.ACTUATOR_STATE", self._actuator_msg())
        if self.publish_clock and t >= nx["clock"] - 1e-9:
            nx["clock"] += per["clock"] * max(1, math.floor((t - nx["clock"]) / per["clock"]) + 1)
            c = sim_clock_t()
            c.utime, c.server_id, c.term = utime(t), self.cfg.multihil.client_id, 0
            c.mode = CLOCK_MODE[self.cfg.sim.clock]
            c.warp = self.pacer.warp if not self.pacer.fast else 0.0
            c.step, c.step_us = 0, utime(self.dt)
            self._publish("SIM.CLOCK", c)

    def _truth_msg(self, tr: Truth):
        m = ground_truth_t()
        m.utime, m.vehicle = utime(tr.t), self.vid
        m.eta, m.nu, m.nu_dot = list(tr.eta), list(tr.nu), list(tr.nu_dot)
        m.current_ned_mps = list(tr.current_ned)
        m.altitude_m, m.water_depth_m = tr.altitude_m, tr.water_depth_m
        m.latitude_deg, m.longitude_deg = tr.latitude_deg, tr.longitude_deg
        return m

    def _actuator_msg(self):
        a = self.model.act
        m = actuator_state_t()
        m.utime, m.vehicle = utime(self.model.t), self.vid
        m.rudder_rad, m.stern_plane_rad, m.prop_rpm = a.rudder, a.stern, a.rpm
        m.thrust_n, m.prop_torque_nm = a.thrust, a.torque
        m.command_stale = self.stale
        m.last_command_utime = self.last_cmd_utime
        return m

    def _health(self, now: float) -> None:
        cpu = os.times()
        wall = now - self._wall_health
        load = ((cpu.user + cpu.system) - (self._cpu0.user + self._cpu0.system)) / wall if wall > 0 else 0.0
        self._cpu0, self._wall_health = cpu, now
        m = process_health_t()
        m.utime, m.vehicle, m.process, m.pid = utime(self.model.t), self.vid, "sim", os.getpid()
        m.messages_received = sum(s.stats.received for s in self.rx.subscriptions)
        m.decode_errors = self.rx.decode_errors
        m.queue_overflows = 0  # the Python LCM binding does not expose its drops
        m.cpu_load = load
        self._publish(f"{self.vid}.HEALTH", m)

    # ---------------------------------------------------------------- loop
    def _drain(self, timeout_s: float) -> None:
        fd = self.lc.fileno()
        ready, _, _ = select.select([fd], [], [], timeout_s)
        while ready:
            self.lc.handle()
            ready, _, _ = select.select([fd], [], [], 0.0)

    def run(self) -> int:
        cfg = self.cfg
        self._t_start = self.model.t
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, lambda *_: setattr(self, "stop_requested", True))
        duration = cfg.sim.duration_s
        print(f"sim: {self.vid} running: clock={cfg.sim.clock} warp={self.pacer.warp:g}"
              f"{' (fast)' if self.pacer.fast else ''} physics={cfg.sim.physics_rate_hz:g}Hz "
              f"sensors={','.join(s.name for s in self.sensors)} "
              f"publish_clock={'yes' if self.publish_clock else 'no'}", flush=True)
        if cfg.sim.clock != "stepped" and self.mh is None:
            self._outputs()   # stepped, multi-HIL: nothing until the global clock says when
        self.pacer.restart(self.model.t)
        wall_start = time.monotonic()
        steps0 = self.model.steps
        health_period = cfg.sim.health_period_s
        while not self.stop_requested:
            if self.mh is not None:
                self.mh.poll()
            now = time.monotonic()
            if now - self._wall_health >= health_period:
                self._health(now)
            if duration > 0 and self.model.t - self._t_start >= duration - 1e-9:
                break
            if self.pacer.may_step(self.model.t, now):
                self._drain(0.0)
                self._check_stale()
                self.model.step()
                self._outputs()
            else:
                self._drain(min(self.pacer.wait_s(self.model.t, now), 0.1))
        if self.mh is not None:
            self.mh.close()
        wall = time.monotonic() - wall_start
        steps = self.model.steps - steps0
        print(f"sim: {self.vid} stopped at t={self.model.t:.2f}s after {steps} steps in "
              f"{wall:.2f}s wall ({steps * self.dt / wall if wall > 0 else 0:.1f}x real time), "
              f"{self.published} messages published, {self.rx.decode_errors} decode errors, "
              f"{self.rejected_commands} commands rejected, {self.stale_events} stale events",
              flush=True)
        return 0

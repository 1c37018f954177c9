"""The environment node plugged into a simulator (sim.hil.Simulator).

The simulator calls poll() once per loop and close() at the end; the rest is
set up here so that hil.py carries only those lines:

- free-running (realtime, scaled): the simulator's steps are paced by the
  node's global clock, and it joins the world at the global time;
- lockstep (simulation.clock: lockstep): the simulator follows SIM.CLOCK as in
  lockstep on its own (each clock the node accepted: one time rule, one count),
  registers as participant `<VEHICLE>.sim`, reports each step
  done once its physics reached it and its outputs are out, and holds every
  actuator command until its time stamp (a command for t_n acts from t_n on,
  whichever arrives first: the clock or the command);
- a client adopts the server's world (currents, waves, bathymetry, ocean, origin).

It changes the simulator only through the simulator's extension points
(docs/simulator.md, "Extension points"): set_clock_source(), join_at(),
follow_clock(), set_command_filter() (by the LockstepFollower),
replace_world() and clock_started; never its internals.
"""

from __future__ import annotations

import math

from sim.bathymetry import BathymetryError
from sim.environment import Environment
from sim.lockstep_follow import LockstepFollower
from sim.multihil.clock import LocalClock
from sim.multihil.election import Timing
from sim.multihil.node import EnvNode, NodeConfig
from sim.ocean import OceanError


def apply_cli(cfg, args) -> None:
    """Command-line overrides of the multihil section (python -m sim ...)."""
    mh = cfg.multihil
    if args.multihil:
        mh.enabled = True
    for name, attr in (
        ("priority", "priority"),
        ("clock_offset_us", "clock_offset_us"),
        ("clock_drift_ppm", "clock_drift_ppm"),
    ):
        if getattr(args, name) is not None:
            setattr(mh, attr, getattr(args, name))


def node_config(cfg) -> NodeConfig:
    mh, s = cfg.multihil, cfg.sim
    mode = s.clock
    return NodeConfig(
        mh.client_id,
        cfg.vehicle_id,
        mh.priority,
        list(mh.needs),
        mh.sample_rate_hz,
        mode,
        s.warp if mode == "scaled" else 1.0,
        s.clock_rate_hz,
        mh.step_s,
        mh.lockstep_participants,
        list(mh.lockstep_names),
        mh.lockstep_timeout_s,
        mh.heartbeat_hz,
        mh.sync_hz,
        Timing(join_window_s=mh.join_window_s, failover_timeout_s=mh.failover_timeout_s),
    )


class SimHook:
    def __init__(self, sim) -> None:
        self.sim = sim
        cfg = sim.cfg
        ncfg = node_config(cfg)
        self.lockstep = ncfg.mode == "lockstep"
        if sim.pacer.fast:
            raise ValueError("multihil: --fast has no clock to share; use scaled time or lockstep (--clock lockstep)")
        steps = ncfg.step_s / sim.dt
        if self.lockstep and (steps < 0.999 or abs(steps - round(steps)) > 1e-6):
            raise ValueError(
                f"multihil: step_s = {ncfg.step_s:g} s must be a whole number of physics steps ({sim.dt:g} s)"
            )
        self.log = lambda line: print(line, flush=True)
        self.node = EnvNode(
            ncfg,
            sim.lc,
            sim.model.env,
            LocalClock(cfg.multihil.clock_offset_us, cfg.multihil.clock_drift_ppm),
            position=self._position,
            on_env=self._adopt,
            log=self.log,
            drops=sim.time_drops,
            on_clock=self._on_clock if self.lockstep else None,
        )
        self.joined = False
        self.env_errors = 0
        if self.lockstep:
            # the simulator's part in lockstep: held commands, its step reports
            self.follow = LockstepFollower(sim)
        else:
            sim.set_clock_source(self)

    # ------------------------------------------------------------ callbacks
    def _position(self) -> tuple[float, float, float, float] | None:
        if not (self.joined or self.sim.clock_started):
            return None
        x = self.sim.model.dyn.x
        return self.sim.model.t, x[0], x[1], x[2]

    def global_now_s(self) -> float | None:
        """The simulator's clock source (sim.clock.ClockSource): the node's global
        time, once the simulator joined the world at it."""
        g = self.node.global_now_us()
        return None if g is None or not self.joined else g / 1e6

    def _adopt(self, m) -> bool:
        """The server's world replaces ours, in place: every part holding it sees the change."""
        params = Environment.params_from_env_model(m)
        try:
            fresh = Environment(params, self.sim.cfg.path.parent)
        except (BathymetryError, OceanError, OSError) as exc:
            self.env_errors += 1
            self.log(f"multihil: cannot build the server's world ({exc}); keeping this one")
            return False
        if fresh.bathymetry.sha256 != m.bathymetry_sha256:
            self.env_errors += 1
            self.log(f"multihil: bathymetry {m.bathymetry_ref} differs from the server's (SHA-256); keeping this one")
            return False
        grid = fresh.ocean.grid if fresh.ocean is not None else None
        if grid is not None and grid.sha256 != m.ocean_grid_sha256:
            self.env_errors += 1
            self.log(f"multihil: ocean grid {m.ocean_grid_ref} differs from the server's (SHA-256); keeping this one")
            return False
        self.sim.replace_world(fresh)
        return True

    def _on_clock(self, m) -> None:
        self.sim.follow_clock(m.utime)
        self.follow.on_clock(m)

    # -------------------------------------------------------------- loop
    def poll(self) -> None:
        node, sim = self.node, self.sim
        node.poll()
        if not self.lockstep:
            if not self.joined and node.joined:
                self.joined = True
                sim.join_at(math.floor(node.global_now_us() / 1e6 / sim.dt) * sim.dt)
            return
        self.joined = sim.clock_started
        self.follow.poll()

    def close(self) -> None:
        if self.lockstep:
            self.follow.part.leave()
        n = self.node
        self.log(
            f"multihil: {n.cfg.client_id}: {n.role} (term {n.term}) at the end; "
            f"{n.clock_messages} clock messages, {n.clock_regressions} regressions, "
            f"{n.samples_received} env samples, {n.sample_mismatches} mismatches, "
            f"{n.election.elections_won} elections won, {n.election.step_downs} step-downs, "
            f"{n.rx.decode_errors} decode errors, {n.election.gaps} gaps "
            "(time drops: the simulator's summary)"
        )
        n.stop()

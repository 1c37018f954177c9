"""The launcher's core: start and supervise one host's part of a scenario.

`Launcher` starts the recorder (auv-recorder, or lcm-logger if chosen), the files
the run uses annotated into the log, the simulators, the onboard navigation
filters (vehicles with `nav: ekf`) and the auv-frontseat of each vehicle flown
from its backseat (tools/launch/backseat.py), the managers; then the global
clock starts.
The mission ends when every vehicle's navigator is done, aborted or failed, or at
the time limit; Ctrl-C, SIGTERM or any process dying ends it too. Everything is
stopped a kind at a time (managers, filters, simulators), the recorder last, so
the log holds the end.

In a lockstep world (the launcher's clock, or the simulators' with the launcher
taking part) the end is a step: the first whose time is after every vehicle's
end (or at the time limit); the world finishes it and is stepped no further.
The launcher then writes the end into the log (annotation `mission end`,
stamped with that step's time), where auv-recorder's record of the world ends,
before it stops anything, so the log also holds the processes' exits and the
summary (`end`) after the mark.

A scenario's planned faults (`faults:`, tools/scenario/faults.py) are applied
at their sim time: a lost vehicle's processes are killed and it counts as
over ("lost"), not as a death.

This module is what other front ends reuse (the host agents' part,
tools/hosts/agent_part.py, starts the same processes); the command line is
tools/launch/cli.py, which may import the agents, never the other way round.
"""

from __future__ import annotations

import json
import subprocess
import time
from pathlib import Path

from auv import lockstep_t
from auvlcm import programs
from auvlcm.chanfilter import FilteredLcm
from auvlcm.paths import ROOT
from auvlcm.url import with_receive_buffer
from sim.multihil.lockstep import lockstep_msg
from tools.launch.annotate import Annotator
from tools.launch.backseat import FrontseatPort, frontseat_cmd
from tools.launch.fault_step import FaultStepper, takes_part
from tools.launch.lockstep_names import RADIO, participants
from tools.launch.mission_watch import MissionWatch
from tools.launch.procs import TIER_FILTER, TIER_MANAGER, TIER_SIMULATOR, Child, stop_together
from tools.launch.recorder_cmd import recorder_cmd, recorder_takes_part
from tools.launch.worldclock import WorldClock
from tools.scenario import radio_section
from tools.scenario.scenario_file import Scenario

# the exit status of each result (auv-launch exits with it)
EXIT = {"done": 0, "aborted": 3, "failed": 4, "died": 5, "time limit": 6, "interrupted": 130}
STARTUP_TIMEOUT_S = 90.0
END_WAIT_S = 5.0  # at most this long for the last step's reports (tools/launch/fault_step.py)
CHILD_CHECK_S = 0.05  # how often the loops look for a child that exited
PTY_WAIT_S = 10.0  # at most this long for the radio model to make its ptys (start_radio)


def nav_configs(
    sc: Scenario, sim_configs: dict[str, Path], out: Path, build: Path
) -> tuple[dict[str, Path], list[str]]:
    """The nav config of each vehicle flown on the onboard filter (`nav: ekf`):
    the scenario's file, or one derived from the vehicle's merged simulator
    configuration (python/tools/nav/navconf.py); each checked by auv-nav itself."""
    from sim.config import load
    from tools.nav.navconf import nav_config_text

    paths, errors = {}, []
    for v in sc.vehicles:
        if v.nav.source != "ekf" or v.id not in sim_configs:
            continue
        path = v.nav.config
        if path is None:
            path = out / f"{v.id}.nav"
            path.write_text(nav_config_text(load(sim_configs[v.id])))
        run = subprocess.run(
            [str(build / "bin" / "auv-nav"), "--config", str(path), "--check"], capture_output=True, text=True
        )
        if run.returncode != 0:
            errors.append(f"{v.where}: {v.id}.nav: {path} does not load:")
            errors += ["  " + ln for ln in (run.stdout + run.stderr).strip().splitlines()]
        paths[v.id] = path
    return paths, errors


def check_plans(sc: Scenario, build: Path) -> list[str]:
    """`chasm check` every plan with its parameters before anything starts."""
    errors, done = [], set()
    for v in sc.vehicles:
        for m in v.managers:
            key = (m.plan, tuple(sorted(m.params.items())), tuple(m.plugin_path))
            if key in done:
                continue
            done.add(key)
            cmd = [str(build / "bin" / "chasm"), "check"]
            for d in m.plugin_path or [build / "plugins"]:
                cmd += ["-P", str(d)]
            for k, val in m.params.items():
                cmd += ["-D", f"{k}={val}"]
            run = subprocess.run(cmd + [str(m.plan)], capture_output=True, text=True)
            if run.returncode != 0:
                errors.append(f"{m.where}: {v.id}.{m.name}: plan {m.plan} does not load:")
                errors += ["  " + ln for ln in (run.stdout + run.stderr).strip().splitlines()]
    return errors


def manager_cmd(build: Path, url: str, vid: str, m, key_file: Path | None = None) -> list[str]:
    """The command line of a scenario's manager m (tools.scenario) of vehicle vid;
    key_file: the scenario's team keys, which the manager then requires."""
    return programs.chasm_manager(
        build,
        plan=m.plan,
        bind=m.bind,
        vehicle=vid,
        name=m.name,
        lcm_url=url,
        rate_hz=m.rate_hz,
        status_rate_hz=m.status_rate_hz,
        plugin_path=m.plugin_path or [build / "plugins"],
        params=m.params,
        key_file=key_file,
    )


class Launcher:
    def __init__(
        self,
        sc: Scenario,
        args,
        url: str,
        sim_configs: dict[str, Path],
        nav_configs: dict[str, Path] | None = None,
        agents: bool = False,
        frontseats: dict[str, FrontseatPort] | None = None,
    ) -> None:
        self.sc, self.args, self.url, self.sim_configs = sc, args, url, sim_configs
        self.nav_configs = nav_configs or {}
        self.frontseats = frontseats or {}  # the backseat vehicles' frontseat ports (tools/launch/backseat.py)
        self.agents = agents
        self.host = args.host
        self.out: Path = args.out
        self.build = args.build
        # filtered: the launcher wakes for what it watches, not for every sensor
        self.lc = FilteredLcm(self.child_url)
        self.mine = sc.vehicles_on(self.host)
        self.own_clock = sc.time.source == "launcher" and (self.host is None or self.host == sc.time.host)
        # with --agents the log host's agent records, not this process
        self.own_log = not agents and sc.log_enabled and (self.host is None or self.host == sc.log_host)
        self.watch = MissionWatch(self.lc, sc, self.frontseats)
        # with agents the log host's agent records what the scenario names
        self.recorder = sc.log_recorder if agents else (args.recorder or sc.log_recorder)
        # lcm-logger's queue of 30 overflows on a burst of annotations: paced for it;
        # auv-recorder takes a burst whole
        self.notes = Annotator(self.lc, f"launcher@{self.host or 'all'}", ROOT, paced=self.recorder == "lcm-logger")
        self.clock = (
            WorldClock(
                self.lc,
                sc.time.mode,
                args.warp or sc.time.warp,
                sc.time.step_s,
                participants(sc, recorder_takes_part(sc, self.recorder)),
                before_step=self.apply_faults,
                hold=self._ended_before,
            )
            if self.own_clock
            else None
        )
        self.logger: Child | None = None
        self._next_child_check = 0.0
        self.children: list[Child] = []
        self.stop_reason = ""
        self.faults = list(sc.faults)  # planned, in time order (tools/scenario/faults.py)
        # a world stepped by the simulators: the launcher takes part, to kill between steps
        self.fault_step = (
            FaultStepper(
                self.lc, self._lost_by, self._settled, self.apply_faults, self._ended_before, track=bool(sc.faults)
            )
            if not self.clock and takes_part(sc, self.host, sim_configs.values())
            else None
        )
        self.end_us: int | None = None  # the step the world ended at (lockstep), else when the watch saw the end
        self.log_path = self.out / sc.log_file
        self.recorder_stats = self.out / "recorder.json"

    @property
    def child_url(self) -> str:
        """Every process hears the whole world: a large receive buffer, so a busy
        moment does not make the kernel drop what the process has not read yet."""
        return with_receive_buffer(self.url)

    # ------------------------------------------------------------ start
    def _start(self, child: Child) -> Child:
        child.start()
        self.children.append(child)
        self.notes.event("start", f"{child.name} pid {child.pid}: {' '.join(child.cmd)}", utime=self.watch.sim_time_us)
        return child

    def start_logger(self) -> None:
        """The recorder: auv-recorder (c/recorder, loses nothing it receives,
        counts what it could not) or lcm-logger (its subscription queue holds
        30 messages and drops 1-2 % of a busy fast-time run)."""
        self.log_path.unlink(missing_ok=True)
        self.recorder_stats.unlink(missing_ok=True)
        cmd = recorder_cmd(self.recorder, self.url, self.log_path, self.recorder_stats, self.build)
        self.logger = Child("logger", cmd, self.out / "logger.out")
        self.logger.start()
        # lcm-logger: listening once its file exists; recording once our probe shows up in
        # it. auv-recorder: listening once its file exists too (it opens its socket
        # first, so the note below is in every log: two runs count the same events),
        # recording once the first message is in the file (its own lockstep
        # registration, sent as it starts), asked every 10 ms.
        # lcm-logger may create its file before it subscribes (a loaded fresh-clone run
        # lost the note and waited 20 s for a byte): while its file stays empty the
        # note is sent again every 0.5 s, so a log may hold it more than once.
        deadline = time.monotonic() + 20
        next_note = 0.0
        while time.monotonic() < deadline and self.logger.poll() is None:
            if self.log_path.exists():
                if time.monotonic() >= next_note:
                    self.notes.event("logger", f"{self.recorder} pid {self.logger.pid} recording {self.log_path.name}")
                    next_note = time.monotonic() + (0.5 if self.recorder == "lcm-logger" else float("inf"))
                if self.recorder == "lcm-logger":
                    time.sleep(0.3)
                if self.log_path.stat().st_size > 0:
                    return
            time.sleep(0.01 if self.recorder == "auv-recorder" else 0.05)
        raise RuntimeError(f"{self.recorder} did not start recording: {self.logger.tail()}")

    def recorder_counts(self) -> dict | None:
        """auv-recorder's counts at exit (received, written, dropped, missed), if it ran."""
        try:
            return json.loads(self.recorder_stats.read_text())
        except (OSError, ValueError):
            return None

    def annotate(self) -> None:
        self.notes.run(self.sc, self.sim_configs, self.nav_configs)

    def sim_cmd(self, vid: str) -> list[str]:
        # On the launcher's clock every simulator runs lockstep; otherwise their configuration decides.
        clock = "lockstep" if self.sc.time.source == "launcher" else None
        return programs.simulator(self.sim_configs[vid], lcm_url=self.child_url, clock=clock)

    def manager_cmd(self, vid: str, m) -> list[str]:
        return manager_cmd(self.build, self.child_url, vid, m, self.sc.key_file)

    def nav_cmd(self, v) -> list[str]:
        return programs.auv_nav(
            self.build, config=self.nav_configs[v.id], vehicle=v.id, lcm_url=self.child_url, rate_hz=v.nav.rate_hz
        )

    def front_cmd(self, v) -> list[str]:
        f = v.front_estimate
        return programs.auv_front_estimate(
            self.build,
            vehicle=v.id,
            lcm_url=self.child_url,
            rate_hz=f.rate_hz,
            max_age_s=f.max_age_s,
            max_depth_m=f.max_depth_m,
        )

    def frontseat_cmd(self, v) -> list[str]:
        return frontseat_cmd(self.build, self.child_url, v.id, self.frontseats[v.id], v.backseat)

    def start_all(self) -> None:
        if self.own_log:
            self.start_logger()
            self.annotate()
        for v in self.mine:
            self._start(Child(f"{v.id}.sim", self.sim_cmd(v.id), self.out / f"{v.id}.sim.out", tier=TIER_SIMULATOR))
        for v in self.mine:  # the onboard filter or the frontseat's driver, before the managers that read it
            if v.id in self.nav_configs:
                self._start(Child(f"{v.id}.NAV", self.nav_cmd(v), self.out / f"{v.id}.nav.out", tier=TIER_FILTER))
            if v.id in self.frontseats:
                out = self.out / f"{v.id}.frontseat.out"
                self._start(Child(f"{v.id}.FRONTSEAT", self.frontseat_cmd(v), out, tier=TIER_FILTER))
            if v.front_estimate is not None:  # after the filter whose NAV it reads
                out = self.out / f"{v.id}.front.out"
                self._start(Child(f"{v.id}.FRONT", self.front_cmd(v), out, tier=TIER_FILTER))
        for v in self.mine:
            for m in v.managers:
                out = self.out / f"{v.id}.{m.name}.out"
                self._start(Child(f"{v.id}.{m.name}", self.manager_cmd(v.id, m), out, tier=TIER_MANAGER))
        if self.sc.radio is not None:
            self.start_radio()

    def start_radio(self) -> None:
        """The surface radio (docs/radio.md): its model and the shore gateway on the
        clock's host, a gateway for each vehicle of this host (`auv-radio`, the
        vehicle's driver, on its radio modem's pty that the model makes in the run
        folder). They follow SIM.CLOCK; the model takes part in the lockstep
        (lockstep_names.RADIO: the world waits for it at every step), the gateways do not."""
        r, url = self.sc.radio, self.child_url
        # the ptys are the clock's host's: a vehicle of another host has no radio yet (docs/radio.md)
        pipes = {v.id: self.out / f"{v.id}.radio.pty" for v in self.sc.vehicles_on(self.sc.time.host)}
        if self.host is None or self.host == self.sc.time.host:
            ids = [v.id for v in self.sc.vehicles]
            settings = radio_section.model_settings(r)
            shore = r.shore_lcm_url or None  # the shore's own network, or the world's
            cmd = programs.radio_sim(
                vehicles=ids, lcm_url=url, settings=settings, pipes=pipes, lockstep_name=RADIO, shore_lcm_url=shore
            )
            self._start(Child("SHORE.radio", cmd, self.out / "radio.out", tier=TIER_SIMULATOR))
            # the gateways open the model's ptys at once rather than after a retry's backoff
            deadline = time.monotonic() + PTY_WAIT_S
            while not all(p.is_symlink() for p in pipes.values()) and time.monotonic() < deadline:
                time.sleep(0.02)
            cmd = programs.radio_shore(
                vehicles=ids, lcm_url=shore or url, acoustic=r.acoustic, key_file=self.sc.key_file
            )
            shore_out = self.out / "shore_gateway.out"
            gateway = Child("SHORE.gateway", cmd, shore_out, tier=TIER_MANAGER)
            self._start(gateway)
            # the world starts once the model registers, which waits for the vehicles' gateways
            # (below): so started after the shore's is ready, none of them misses the start
            deadline = time.monotonic() + STARTUP_TIMEOUT_S
            while time.monotonic() < deadline and gateway.poll() is None:
                if shore_out.exists() and "auv-radio-shore: ready" in shore_out.read_text(errors="replace"):
                    break
                time.sleep(0.02)
        for v in self.mine:
            if v.id not in pipes:
                print(f"launch: {v.id} is not on the radio's host {self.sc.time.host}: no radio gateway", flush=True)
                continue
            cmd = programs.radio_vehicle(
                self.build,
                vehicle=v.id,
                spool=self.out / f"{v.id}.radio_spool",
                lcm_url=url,
                port=pipes[v.id],
                team_index=r.acoustic.get(v.id),
                report_period_s=r.report_period_s,
                end_manager=v.end_manager,
                key_file=self.sc.key_file,
                peers=[p for p in pipes if p != v.id] if r.peers else (),
            )
            self._start(Child(f"{v.id}.radio", cmd, self.out / f"{v.id}.radio.out", tier=TIER_MANAGER))

    # ------------------------------------------------------------ supervise
    def _dead(self) -> Child | None:
        return next((c for c in self.children if not c.stopping and c.poll() is not None), None)

    def _dead_by_now(self) -> Child | None:
        """_dead(), asked at most every CHILD_CHECK_S: the loops turn at every
        message, and a poll of every child each turn cost a system call per
        child per wake-up (5 per vehicle)."""
        now = time.monotonic()
        if now < self._next_child_check:
            return None
        self._next_child_check = now + CHILD_CHECK_S
        return self._dead()

    def wait_ready(self, stop) -> str:
        """Hold time before step 0 until every participant of the world registered
        (the clock's host), or until every process reported (the other hosts)."""
        deadline = time.monotonic() + STARTUP_TIMEOUT_S
        ready = self.clock.ready if self.clock else self.watch.all_ready
        while time.monotonic() < deadline:
            if stop():
                return "interrupted"
            if self._dead_by_now():
                return "died"
            self.watch.handle(0.1)
            if self.fault_step:
                self.fault_step.poll()  # registers before step 0
            if ready():
                return ""
        missing = self.clock.not_ready() if self.clock else self.watch.not_ready()
        self.stop_reason = f"not ready after {STARTUP_TIMEOUT_S:.0f} s: {', '.join(missing)}"
        return "died"

    def supervise(self, stop) -> str:
        t = self.sc.time
        wall0 = time.monotonic()
        next_progress = wall0 + self.args.progress
        if self.clock:
            self.clock.start()
        while True:
            if stop():
                return "interrupted"
            if self._dead_by_now():
                return "died"
            if self.clock:
                self.clock.advance()
            # blocks until a message comes (a report, a status) or the next step is due
            self.watch.handle(self.clock.wait_s() if self.clock else 0.1)
            if self.fault_step:
                self.fault_step.poll()
            elif not self.clock:  # free-running: when the watch sees the time
                self.apply_faults(self.watch.sim_time_us)
            if self.clock or self.fault_step:  # lockstep: the end is the step the world was held at
                held = self._held_us(stop)
                if held is not None:
                    self.end_us = held
                    return self._result_at(held)
            else:
                outcome = self.watch.outcome()
                if outcome:
                    return outcome
                if self.watch.sim_time_us / 1e6 >= t.limit_s:
                    return self._result_at(self.watch.sim_time_us)
            now = time.monotonic()
            if t.wall_limit_s and now - wall0 >= t.wall_limit_s:
                self.stop_reason = f"wall-clock limit {t.wall_limit_s:g} s reached"
                return "time limit"
            if self.args.progress > 0 and now >= next_progress:
                next_progress = now + self.args.progress
                sim_s = self.watch.sim_time_us / 1e6
                waits = self.clock.waiting_for() if self.clock else []
                print(
                    f"launch: t={sim_s:8.1f} s (x{sim_s / max(now - wall0, 1e-9):.1f})  "
                    + "  ".join(self.watch.progress())
                    + (f"  (step waits for {', '.join(waits)})" if waits else ""),
                    flush=True,
                )

    def _ended_before(self, t_us: int) -> bool:
        """Whether the mission ended before step time t_us, or that step reaches the
        time limit: asked with every earlier step reported (the launcher's clock) or
        at the clock of that step (the simulators'), when everything stamped before
        t_us has reached the watch (sim/multihil/lockstep.py: a step's messages go
        out before its report, the next clock after every report)."""
        self.watch.handle(0.0)
        return self.watch.outcome(before_us=t_us) is not None or t_us / 1e6 >= self.sc.time.limit_s

    def _held_us(self, stop) -> int | None:
        """The time of the step the world was held at, once all of it is in: the
        launcher's clock holds when every participant reported it; in a world the
        simulators step, the launcher waits for their reports of it (they repeat
        them while no clock follows), at most END_WAIT_S."""
        if self.clock:
            return self.clock.held_us
        step = self.fault_step
        if step is None or step.held_at is None:
            return None
        names = participants(self.sc, recorder_takes_part(self.sc, self.recorder))
        names -= self._lost_by(step.held_at[1])
        deadline = time.monotonic() + END_WAIT_S
        while not step.finished(names, self._exited) and time.monotonic() < deadline and not stop():
            self.watch.handle(0.05)
        return step.held_at[1]

    def _result_at(self, t_us: int) -> str:
        """The mission's outcome as of step time t_us: the worst vehicle outcome, or the time limit."""
        outcome = self.watch.outcome(before_us=t_us)
        if outcome:
            return outcome
        self.stop_reason = f"mission time limit {self.sc.time.limit_s:g} s reached"
        return "time limit"

    def _lost_by(self, t_us: int) -> set[str]:
        """The participants of the vehicles lost at or before t_us (sim time)."""
        vids = {f.vehicle for f in self.faults if f.do == "lose" and f.at_s * 1e6 <= t_us + 0.5}
        return {n for n in participants(self.sc, False) if n.split(".", 1)[0] in vids}

    def _settled(self, name: str) -> bool:
        """That participant's process is not running here (gone, or on another host)."""
        c = next((c for c in self.children if c.name == name), None)
        return c is None or c.poll() is not None

    def _exited(self, name: str) -> bool:
        """That participant's process runs here and has exited."""
        c = next((c for c in self.children if c.name == name), None)
        return c is not None and c.poll() is not None

    def apply_faults(self, t_us: int) -> None:
        """The planned faults due by sim time t_us (docs/scenarios.md, "Faults").
        Every host's launcher applies each one to its watch and clock; the host
        that runs the vehicle kills its processes. Lockstep: called between the
        steps (tools/launch/fault_step.py), t_us the first step the vehicle misses."""
        while self.faults and self.faults[0].at_s * 1e6 <= t_us + 0.5:
            f = self.faults.pop(0)
            t = t_us / 1e6
            if f.do != "lose":  # the simulator applies it (its configuration has the time)
                text = f"{f.vehicle} {f.do} at t={t:.1f} s (planned at {f.at_s:g} s, {f.where})"
                print(f"launch: fault: {text}", flush=True)
                self.notes.event("fault", text, vehicle=f.vehicle, utime=t_us)
                continue
            prefix = f"{f.vehicle}."
            names = {n for n in participants(self.sc, False) if n.startswith(prefix)}
            killed = [c for c in self.children if c.name.startswith(prefix) and not c.stopping]
            for c in killed:
                c.kill()
            if self.clock:
                self.clock.lose(names)
            for n in sorted(names):  # a world stepped by the simulators stops waiting for them too
                self.lc.publish("SIM.LOCKSTEP", lockstep_msg(n, lockstep_t.KIND_LEAVE, 0, 0).encode())
            self.watch.lose(f.vehicle, t)
            text = (
                f"{f.vehicle} lost at t={t:.1f} s (planned at {f.at_s:g} s, "
                f"{f.where}): killed {', '.join(c.name for c in killed) or 'nothing on this host'}"
            )
            print(f"launch: fault: {text}", flush=True)
            self.notes.event("fault", text, vehicle=f.vehicle, utime=t_us)

    def mark_end(self) -> None:
        """The mission's end into the log, before anything stops: auv-recorder
        records nothing of the world after it (the launcher's notes of the stop
        and the summary still), and the report cuts every series there."""
        if self.end_us is None:
            self.end_us = self.watch.sim_time_us  # not held (interrupted, a death, free-running time)
        # whoever ends the world (its clock, or the launcher taking part); in free-running time, who records
        if self.clock or self.fault_step or ((self.own_log or self.agents) and self.sc.time.source != "launcher"):
            self.notes.event("mission end", json.dumps({"sim_time_s": self.end_us / 1e6}), utime=self.end_us)

    def stop_all(self, result: str) -> None:
        self.mark_end()
        if self.fault_step:
            self.fault_step.close()  # the world must not wait for the launcher while it stops
        dead = self._dead()
        if dead is not None:
            self.stop_reason = (
                f"{dead.name} (pid {dead.pid}) exited with status {dead.poll()}; last output:\n{dead.tail()}"
            )
        codes = stop_together(self.children)
        for c in reversed(self.children):
            if c is not dead:
                self.notes.event(
                    "exit", f"{c.name} pid {c.pid} stopped, status {codes[c.name]}", utime=self.watch.sim_time_us
                )
        self.notes.event("end", json.dumps(self.summary(result)), utime=self.watch.sim_time_us)
        if self.logger is not None:
            # lcm-logger flushes every 100 ms: let the end reach the file (auv-recorder
            # itself takes in everything on its way before it writes out and exits)
            if self.recorder == "lcm-logger":
                time.sleep(0.3)
            self.logger.stop()

    def summary(self, result: str) -> dict:
        vehicles = self.watch.vehicle_summary()
        # an aborted or failed mission names what fired: "AUV1 nav_stale; AUV3 leak"
        causes = "; ".join(f"{vid} {v['cause']}" for vid, v in vehicles.items() if v["cause"])
        return {
            "scenario": self.sc.name,
            "host": self.host,
            "outcome": result,
            "exit_code": EXIT[result],
            "reason": self.stop_reason or causes,
            "sim_time_s": (self.watch.sim_time_us if self.end_us is None else self.end_us) / 1e6,
            "vehicles": vehicles,
            "log": str(self.log_path) if self.own_log else None,
            "dropped": self.watch.dropped(),
        }

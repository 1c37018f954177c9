#!/usr/bin/env python3
"""Record an LCM log of a simulated survey: the navigation filter's test data.

    auv-survey-log --out run.lcmlog [--config missions/sim/remus100_survey.yaml]
                  [--set sensors.dvl.dropout=0.2]... [--lines 4 --length 460 ...]

Runs the real simulator (python/sim) in lockstep and drives it from here:
this script is the global clock (SIM.CLOCK, 0.1 s steps) and a scripted survey
controller (tools/nav/survey_pilot.py) steering by the simulator's black-box INS
(<V>.NAV). Each step waits for the simulator's output and for every other
participant of the lockstep (a filter under test, auv-nav, reports its steps
on SIM.LOCKSTEP), so the run is deterministic (same config and seed, same
sensor data, the same filter output) and as fast as the processes allow.

Everything on the URL is recorded into an LCM log (lcm-logger's format). By
default this script records it itself, in the same loop that waits for each
step: the simulator can never run ahead of the recording, so nothing is lost
however busy the machine is. `--logger lcm-logger` uses the real lcm-logger
instead; on a loaded machine it can fall behind a simulation running at 50x
and drop messages (seen: 179 of 5115 truth samples lost with a 4 MB receive
buffer), which this script detects and reports (exit 3).
`--set key.path=value` overrides one key of the simulator configuration (the
overridden file is written next to the log and annotated into it).
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import time
from pathlib import Path

import lcm

from auv import actuator_state_t, actuators_t, lockstep_t, log_annotation_t, nav_solution_t, sim_clock_t
from auvlcm import programs
from auvlcm.paths import ROOT
from auvlcm.rx import Receiver
from auvlcm.timepolicy import InputGate, TimeDrops
from auvlcm.url import check_local, default_url
from sim.multihil.lockstep import LockstepTracker
from tools.launch.procs import Child
from tools.nav.survey_pilot import Nav, Survey, SurveyPilot

DEFAULT_CONFIG = ROOT / "missions" / "sim" / "remus100_survey.yaml"
STEP_S = 0.1


def apply_overrides(text: str, sets: list[str], path: Path = Path("<config>")) -> str:
    """The YAML text with each `a.b.c=value` set (value parsed as YAML). The text
    and every value are read by confcheck (limits, no aliases, no control
    characters); ConfigError (a ValueError to callers' except) on a bad one."""
    from confcheck import Checker
    from confcheck.reader import dump_yaml

    c = Checker.from_text(text, path)
    doc = c.plain(c.root)
    c.raise_errors()
    doc = doc if isinstance(doc, dict) else {}
    if any(item.startswith("sensors.") for item in sets) and not doc.get("sensors"):
        # an absent section means "every sensor at its defaults"; a listed one
        # means "only these": list them all before changing one
        from sim.sensors import FITTED_UNLESS_LISTED

        doc["sensors"] = {name: {} for name in FITTED_UNLESS_LISTED}
    for item in sets:
        key, sep, value = item.partition("=")
        if not sep or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*", key):
            raise ValueError(f"--set {item!r}: expected key.path=value")
        node = doc
        parts = key.split(".")
        for p in parts[:-1]:
            node = node.setdefault(p, {})
            if not isinstance(node, dict):
                raise ValueError(f"--set {item!r}: {p} is not a section")
        v = Checker.from_text(value, Path(f"--set {key}")) if value.strip() else None
        node[parts[-1]] = v.plain(v.root) if v is not None else None
        if v is not None:
            v.raise_errors()
    return dump_yaml(doc)


class Stepper:
    """The global clock plus the scripted controller, over LCM."""

    def __init__(self, lc: lcm.LCM, vehicle: str, pilot: SurveyPilot) -> None:
        self.lc, self.vehicle, self.pilot = lc, vehicle, pilot
        self.rx = Receiver(lc)
        self.nav = Nav()
        self.have_nav = False
        self.sim_utime = -1
        self.seq = 0
        self.clock_utime: int | None = None  # the last SIM.CLOCK this script published
        self.time_drops = TimeDrops("survey_log")
        self._state_gate = InputGate(self.time_drops, f"{vehicle}.ACTUATOR_STATE")
        self.rx.subscribe(f"{vehicle}.NAV", nav_solution_t, self._on_nav, queue_capacity=200)
        self.rx.subscribe(f"{vehicle}.ACTUATOR_STATE", actuator_state_t, self._on_state, queue_capacity=200)
        # whoever else takes part in the lockstep (a filter under test: auv-nav)
        # is waited for too, so it can never fall behind the world on a loaded machine
        self.tracker = LockstepTracker(timeout_s=None)
        self.rx.subscribe("SIM.LOCKSTEP", lockstep_t, lambda _ch, m: self.tracker.on_message(m), queue_capacity=1000)

    def _on_nav(self, _ch: str, m) -> None:
        self.nav = Nav(m.north_m, m.east_m, m.depth_m, m.heading_rad, m.pitch_rad, m.q_radps, m.r_radps)
        self.have_nav = True

    def _on_state(self, _ch: str, m) -> None:
        if self._state_gate.offer(m.utime, self.clock_utime):  # 10^18 must not end a step
            self.sim_utime = m.utime

    def clock(self, utime: int) -> None:
        c = sim_clock_t()
        step_us = int(STEP_S * 1e6)
        c.utime, c.server_id, c.mode, c.warp, c.step_us = (
            utime,
            "survey_log",
            sim_clock_t.MODE_LOCKSTEP,
            0.0,
            step_us,
        )
        # numbered like a lockstep server's steps: the simulator reports each
        # one, and a filter in the world (auv-nav) waits for that report before
        # its clock's solution, so the compass's solution of the step is out
        # first on any load (without numbers every step was "step 0")
        c.step = utime // step_us
        self.lc.publish("SIM.CLOCK", c.encode())
        self.clock_utime = utime

    def step_to(self, utime: int, timeout_s: float) -> None:
        """Release the simulator up to utime and wait until it got there and every
        participant of the lockstep reported the step."""
        deadline = time.monotonic() + timeout_s
        resend = 0.0
        step = utime // int(STEP_S * 1e6)
        while self.sim_utime < utime or self.tracker.waiting_for(step):
            now = time.monotonic()
            if now > deadline:
                raise TimeoutError(f"simulator did not reach t={utime / 1e6:.1f}s")
            if now >= resend:  # the first ticks may come before it subscribed
                self.clock(utime)
                resend = now + 0.5
            self.lc.handle_timeout(50)

    def command(self, utime: int) -> None:
        rudder, stern, rpm = self.pilot.command(utime / 1e6, self.nav)
        a = actuators_t()
        a.utime, a.vehicle = utime, self.vehicle
        a.rudder_rad, a.stern_plane_rad, a.prop_rpm, a.seq = rudder, stern, rpm, self.seq
        self.seq += 1
        self.lc.publish(f"{self.vehicle}.ACTUATORS", a.encode())


class Recorder:
    """Every message on the URL into an LCM log, stamped with wall time as
    lcm-logger does (sim time travels in the messages)."""

    def __init__(self, lc: lcm.LCM, path: Path) -> None:
        self.log = lcm.EventLog(str(path), "w", overwrite=True)
        self.events = 0
        lc.subscribe(".*", self._on_message).set_queue_capacity(10000)

    def _on_message(self, channel: str, data: bytes) -> None:
        self.log.write_event(int(time.time() * 1e6), channel, data)
        self.events += 1

    def close(self) -> None:
        self.log.close()


def count_truth(log: Path, vehicle: str) -> int:
    from auvlcm.log import read_events

    return sum(1 for ev in read_events(log) if ev.channel == f"{vehicle}.TRUTH")


def annotate(lc: lcm.LCM, name: str, text: str, kind: int) -> None:
    note = log_annotation_t()
    note.source, note.kind, note.name, note.text = "survey_log", kind, name, text
    lc.publish("SIM.ANNOTATION", note.encode())


def run(args: argparse.Namespace) -> int:
    url = check_local(args.url)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    cfg_text = apply_overrides(Path(args.config).read_text(encoding="utf-8"), args.set, Path(args.config))
    cfg_path = out.with_suffix(".sim.yaml")
    cfg_path.write_text(cfg_text)
    from sim.config import load

    vehicle = load(cfg_path).vehicle_id  # checked before anything starts (ConfigError: exit 2)
    survey = Survey(
        length_m=args.length,
        spacing_m=args.spacing,
        lines=args.lines,
        depth_m=args.depth,
        surface_s=args.surface_s,
        final_surface=args.final_surface,
        surface_crossovers=args.surface_crossovers,
    )
    lc = lcm.LCM(url)
    stepper = Stepper(lc, vehicle, SurveyPilot(survey))
    logger, recorder = None, None
    if args.logger == "lcm-logger":
        logger = Child(
            "logger",
            programs.lcm_logger(Path(lcm.LCM_BIN_DIR).resolve(), lcm_url=url, log=out),
            out.with_suffix(".logger.out"),
        ).start()
    else:
        recorder = Recorder(lc, out)
    sim = None
    try:
        if logger is not None:
            time.sleep(0.5)  # the logger is listening before anything is said
        annotate(lc, cfg_path.name, cfg_text, log_annotation_t.KIND_SCENARIO)
        annotate(lc, "survey", repr(survey), log_annotation_t.KIND_NOTE)
        sim = Child(
            "sim",
            programs.simulator(cfg_path, lcm_url=url, clock="lockstep"),
            out.with_suffix(".sim.out"),
        ).start()
        t_us, end_us = 0, None
        limit_us = int(min(args.max_s, 1e7) * 1e6)
        stepper.step_to(0, timeout_s=30.0)
        while t_us < limit_us:
            stepper.command(t_us)
            if stepper.pilot.done and end_us is None:
                end_us = t_us + int(args.tail_s * 1e6)
            if end_us is not None and t_us >= end_us:
                break
            t_us += int(STEP_S * 1e6)
            stepper.step_to(t_us, timeout_s=10.0)
    finally:
        if sim is not None:
            sim.stop()
        deadline = time.monotonic() + 0.5  # the last messages reach the log
        while time.monotonic() < deadline:
            lc.handle_timeout(50)
        if logger is not None:
            logger.stop()
        if recorder is not None:
            recorder.close()
    print(
        f"survey_log: {out}: {t_us / 1e6:.1f} sim s, {survey.lines} lines of {survey.length_m:g} m "
        f"({survey.path_length_m():.0f} m of track), pilot {'done' if stepper.pilot.done else 'NOT done'}"
        + ("" if not stepper.time_drops.total else f", {stepper.time_drops.summary()}")
        + ("" if not stepper.rx.decode_errors else f", {stepper.rx.decode_errors} undecodable message(s) dropped")
    )
    # One truth message per 0.1 s step: fewer in the log means the recording
    # lost messages (a starved logger), and the log is not the run.
    logged, steps = count_truth(out, vehicle), t_us // int(STEP_S * 1e6) + 1
    if logged < steps:
        print(f"survey_log: {out}: the logger lost messages ({logged} of {steps} truth samples)", file=sys.stderr)
        return 3
    return 0 if stepper.pilot.done or math.isfinite(args.max_s) else 1


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="log file to write")
    ap.add_argument("--config", default=str(DEFAULT_CONFIG))
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    programs.add_lcm_url_argument(ap, "LCM URL", default=default_url())
    ap.add_argument(
        "--logger",
        choices=("self", "lcm-logger"),
        default="self",
        help="who records the log (default: this script, in step with the simulation)",
    )
    ap.add_argument("--lines", type=int, default=4)
    ap.add_argument("--length", type=float, default=460.0)
    ap.add_argument("--spacing", type=float, default=50.0)
    ap.add_argument("--depth", type=float, default=12.0)
    ap.add_argument("--surface-s", type=float, default=60.0)
    ap.add_argument("--final-surface", action="store_true")
    ap.add_argument("--surface-crossovers", action="store_true", help="surface between lines (GPS fixes)")
    ap.add_argument("--tail-s", type=float, default=5.0, help="sim seconds recorded after the last line")
    ap.add_argument("--max-s", type=float, default=math.inf, help="stop after this many sim seconds")
    try:
        return run(ap.parse_args(argv))
    except (ValueError, TimeoutError, OSError) as exc:
        print(f"survey_log: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

"""The scenario chooses per vehicle what publishes <ID>.NAV: the simulator's
black-box INS (`nav: ins`, the default) or the onboard filter (`nav: ekf`):
the launcher then derives the vehicle's nav config from its simulator
configuration (or takes the one given), moves the INS to <ID>.NAV_INS and
starts auv-nav before the managers."""

from __future__ import annotations

import subprocess
import sys

import yaml
from conftest import ROOT

from auv import nav_solution_t
from auvlcm.log import read_events

LAUNCH = [sys.executable, "-m", "tools.launch"]
SIM = str(ROOT / "missions" / "sim" / "remus100_multihil.yaml")
PLAN = str(ROOT / "tests" / "tools" / "scenarios" / "mission.chasm")  # 1500 rpm for N cycles, then done
BIND = str(ROOT / "missions" / "bindings" / "direct_actuators.bind")


def scenario(tmp_path, vehicles, name="nav"):
    sc = {"name": name, "seed": 3, "time": {"mode": "lockstep", "limit": 60, "wall_limit": 120}, "vehicles": vehicles}
    path = tmp_path / f"{name}.yaml"
    path.write_text(yaml.safe_dump(sc, sort_keys=False))
    return path


def vehicle(vid, nav, east=0.0):
    mgr = {"name": "NAVIGATOR", "plan": PLAN, "bind": BIND, "rate": 10, "params": {"cycles": 150}}
    return {"id": vid, "sim": {"config": SIM, "initial": {"east_m": east}}, "managers": [mgr], "nav": nav}


def launch(path, out, url, env):
    return subprocess.run(
        LAUNCH + [str(path), "--out", str(out), "--lcm-url", url, "--progress", "0"],
        env=env,
        capture_output=True,
        text=True,
        timeout=240,
    )


def test_each_vehicle_flies_on_the_navigation_its_scenario_names(tmp_path, lcm_url, child_env):
    path = scenario(tmp_path, [vehicle("AUV1", "ekf"), vehicle("AUV2", "ins", east=30.0)])
    run = launch(path, tmp_path / "run", lcm_url, child_env)
    assert run.returncode == 0, run.stdout + run.stderr
    sources, notes = {}, set()
    for ev in read_events(tmp_path / "run" / "run.lcmlog"):
        if ev.msg is None:
            continue
        if ev.channel in ("AUV1.NAV", "AUV1.NAV_INS", "AUV2.NAV", "AUV2.NAV_INS"):
            sources.setdefault(ev.channel, set()).add(ev.msg.source)
        if ev.channel == "SIM.ANNOTATION":
            notes.add(ev.msg.name)
    assert sources == {
        "AUV1.NAV": {nav_solution_t.SOURCE_EKF},
        "AUV1.NAV_INS": {nav_solution_t.SOURCE_SIM_INS},
        "AUV2.NAV": {nav_solution_t.SOURCE_SIM_INS},
    }, sources
    assert "AUV1.nav" in notes  # the derived nav config is in the log
    merged = yaml.safe_load((tmp_path / "run" / "AUV1.sim.yaml").read_text())
    assert merged["sensors"]["ins"]["channel"] == "NAV_INS" and set(merged["sensors"]) >= {"ahrs", "dvl", "lbl"}
    assert (tmp_path / "run" / "AUV1.nav.out").exists() and not (tmp_path / "run" / "AUV2.nav.out").exists()


def test_a_bad_nav_choice_or_config_is_refused_before_anything_starts(tmp_path, lcm_url, child_env):
    path = scenario(tmp_path, [vehicle("AUV1", "kalman")])
    run = launch(path, tmp_path / "run1", lcm_url, child_env)
    assert run.returncode == 2
    assert "vehicles[0].nav: expected one of: ins, ekf" in run.stderr, run.stderr
    bad = tmp_path / "bad.nav"
    bad.write_text("gps_noise_m -1\n")
    path = scenario(tmp_path, [vehicle("AUV1", {"source": "ekf", "config": str(bad)})], name="nav2")
    run = launch(path, tmp_path / "run2", lcm_url, child_env)
    assert run.returncode == 2
    assert f"{bad}:1:13: gps_noise_m = -1 is outside" in run.stderr, run.stderr
    assert not (tmp_path / "run2" / "run.lcmlog").exists()


def test_the_launcher_holds_the_clock_until_each_filter_reports(tmp_path, lcm_url):
    """A filter that subscribes after the clock starts misses the first GPS fix:
    the world is ready only once every `nav: ekf` vehicle's NAV_STATUS is seen."""
    import lcm

    from auv import actuator_state_t, chasm_status_t, nav_filter_status_t
    from tools.launch.mission_watch import MissionWatch
    from tools.scenario.scenario_file import load_scenario

    sc = load_scenario(scenario(tmp_path, [vehicle("AUV1", "ekf"), vehicle("AUV2", "ins", east=30.0)]))
    lc = lcm.LCM(lcm_url)
    watch = MissionWatch(lc, sc)

    def publish(channel, msg, vid, manager=None):
        msg.vehicle = vid
        if manager:
            msg.manager = manager
        lc.publish(channel, msg.encode())
        watch.handle(0.5)

    for vid in ("AUV1", "AUV2"):
        publish(f"{vid}.ACTUATOR_STATE", actuator_state_t(), vid)
        publish(f"{vid}.CHASM.NAVIGATOR", chasm_status_t(), vid, "NAVIGATOR")
    assert not watch.all_ready() and watch.not_ready() == ["AUV1.NAV"]
    publish("AUV2.NAV_STATUS", nav_filter_status_t(), "AUV2")  # not a filter this scenario runs
    assert watch.not_ready() == ["AUV1.NAV"]
    publish("AUV1.NAV_STATUS", nav_filter_status_t(), "AUV1")
    assert watch.all_ready()


def test_the_clock_waits_for_a_filter_that_falls_behind(tmp_path, lcm_url):
    """A filter starved of CPU holds the clock like a starved manager does: it is
    a lockstep participant of the launcher's clock (tools/launch/worldclock.py), which
    starts only once it registered and publishes no step it has not finished."""
    import lcm

    from auv import lockstep_t, sim_clock_t
    from sim.multihil.lockstep import lockstep_msg
    from tools.launch.lockstep_names import participants
    from tools.launch.worldclock import WorldClock
    from tools.scenario.scenario_file import load_scenario

    sc = load_scenario(scenario(tmp_path, [vehicle("AUV1", "ekf"), vehicle("AUV2", "ins", east=30.0)]))
    names = participants(sc, recorder=True)
    assert "AUV1.NAV" in names and "AUV2.NAV" not in names and "SIM.RECORDER" in names
    lc = lcm.LCM(lcm_url)
    clock = WorldClock(lc, "lockstep", 1.0, 0.05, names)
    steps: list[int] = []
    lc.subscribe("SIM.CLOCK", lambda _c, d: steps.append(sim_clock_t.decode(d).step))

    def report(name: str, kind: int, step: int = 0) -> None:
        lc.publish("SIM.LOCKSTEP", lockstep_msg(name, kind, step, step * 50_000).encode())
        while lc.handle_timeout(200) > 0:
            pass

    for n in sorted(names - {"AUV1.NAV"}):
        report(n, lockstep_t.KIND_REGISTER)
    assert not clock.ready() and clock.not_ready() == ["AUV1.NAV"]
    report("AUV1.NAV", lockstep_t.KIND_REGISTER)
    assert clock.ready()
    clock.start()
    for step in range(3):
        clock.advance()
        for n in sorted(names - {"AUV1.NAV"}):
            report(n, lockstep_t.KIND_STEP_DONE, step)
        clock.advance()
        assert steps[-1] == step and clock.waiting_for() == ["AUV1.NAV"]  # held for the filter
        report("AUV1.NAV", lockstep_t.KIND_STEP_DONE, step)
    clock.advance()
    while lc.handle_timeout(200) > 0:
        pass
    assert steps == [0, 1, 2, 3]

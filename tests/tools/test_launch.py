"""The launcher over real processes and real LCM: start order, mission end and
exit codes, process death, signals, a SIGKILLed launcher, host split, bad
scenarios. Missions use the test plugin (count_to / fail_after) so they end
on their own after a few sim seconds, in fast time."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import yaml
from conftest import ROOT

from auvlcm.arrays import load_log
from auvlcm.log import read_events
from tools.logs.timeline import state_timeline

HERE = Path(__file__).resolve().parent / "scenarios"
LAUNCH = [sys.executable, "-m", "tools.launch"]
SIM = str(ROOT / "missions" / "sim" / "remus100_multihil.yaml")
BIND = str(ROOT / "missions" / "bindings" / "direct_actuators.bind")


def vehicle(vid, host="local", east=0.0, **params):
    nav = {
        "name": "NAVIGATOR",
        "plan": str(HERE / "mission.chasm"),
        "bind": BIND,
        "rate": 10,
        "params": {"cycles": 60, **params},
    }
    watch = {"name": "WATCHER", "plan": str(HERE / "watcher.chasm"), "bind": str(HERE / "watcher.bind"), "rate": 5}
    return {"id": vid, "host": host, "sim": {"config": SIM, "initial": {"east_m": east}}, "managers": [nav, watch]}


def write_scenario(tmp_path, vehicles, hosts=("local",), limit=60, name="t"):
    sc = {
        "name": name,
        "seed": 5,
        "time": {"mode": "lockstep", "limit": limit, "wall_limit": 120},
        "hosts": list(hosts),
        "vehicles": vehicles,
    }
    path = tmp_path / f"{name}.yaml"
    path.write_text(yaml.safe_dump(sc, sort_keys=False))
    return path


def launch(path, out, url, env, *extra, timeout=180):
    return subprocess.run(
        LAUNCH + [str(path), "--out", str(out), "--lcm-url", url, "--progress", "0", *extra],
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def test_two_vehicles_run_to_the_end_and_the_log_describes_itself(tmp_path, lcm_url, child_env):
    path = write_scenario(tmp_path, [vehicle("AUV1"), vehicle("AUV2", east=40.0, cycles=90)])
    run = launch(path, tmp_path / "run", lcm_url, child_env)
    assert run.returncode == 0, run.stdout + run.stderr
    outcome = json.loads((tmp_path / "run" / "outcome.json").read_text())
    assert outcome["outcome"] == "done" and set(outcome["vehicles"]) == {"AUV1", "AUV2"}
    rec = outcome["recorder"]  # auv-recorder, the default: nothing lost
    assert rec["dropped"] == 0 and rec["missed"] == 0 and rec["written"] == rec["received"] > 0, rec
    assert f"record: {rec['written']} of {rec['received']} messages received written, 0 dropped, 0 missed" in run.stdout

    log = load_log(tmp_path / "run" / "run.lcmlog", keep_messages="SIM.ANNOTATION")
    assert log.stats.undecodable == 0
    for vid, cycles in (("AUV1", 60), ("AUV2", 90)):
        segs = state_timeline(log[f"{vid}.CHASM.NAVIGATOR"])
        running = [s for s in segs if s.run == "running"]
        # The clock waited for every process: the plan started on the first step that had the
        # simulator's data of step 0 (lockstep: a manager works on the steps before), t = 0.05 s,
        # and ran its cycles at 10 Hz.
        assert running[0].path == "run" and running[0].start == 0.05
        assert abs(running[1].start - cycles / 10) < 0.25, segs
        assert segs[-1].run == "done" and segs[-1].path == "stop"
        truth = log[f"{vid}.TRUTH"]
        assert truth.t[0] == 0.0 and truth["eta[0]"][-1] > 2.0  # it moved north under 1500 rpm from rest
    assert log["SIM.CLOCK"].t[-1] >= 9.0

    notes = log.messages["SIM.ANNOTATION"]
    kinds = {(n.kind, n.vehicle, n.name) for n in notes}
    assert (1, "", path.name) in kinds and (1, "AUV2", "AUV2.sim.yaml") in kinds
    assert sum(1 for n in notes if n.kind == 2) == 4  # 2 plans x 2 vehicles
    assert sum(1 for n in notes if n.kind == 0 and n.name.endswith(".bind")) == 4
    assert sum(1 for n in notes if n.kind == 3) == len(list((ROOT / "lcmtypes").glob("*.lcm")))
    starts = [n.text for n in notes if n.kind == 4 and n.name == "start"]
    order = [s.split()[0] for s in starts]
    assert order[:2] == ["AUV1.sim", "AUV2.sim"] and set(order[2:]) == {
        "AUV1.NAVIGATOR",
        "AUV1.WATCHER",
        "AUV2.NAVIGATOR",
        "AUV2.WATCHER",
    }
    end = [n for n in notes if n.kind == 4 and n.name == "end"]
    assert len(end) == 1 and json.loads(end[0].text)["outcome"] == "done"
    merged = yaml.safe_load((tmp_path / "run" / "AUV2.sim.yaml").read_text())
    assert merged["vehicle"]["id"] == "AUV2" and merged["initial"]["east_m"] == 40.0


def test_abort_fail_and_time_limit_give_their_exit_codes(tmp_path, lcm_url, child_env):
    cases = [
        ("aborted", 3, vehicle("AUV1", abort_at="3 s")),
        ("failed", 4, vehicle("AUV1", fail="true")),
        ("time limit", 6, vehicle("AUV1", cycles=100000)),
    ]
    for i, (what, code, veh) in enumerate(cases):
        path = write_scenario(tmp_path, [vehicle("AUV2"), veh], limit=20, name=f"c{i}")
        run = launch(path, tmp_path / f"run{i}", lcm_url, child_env)
        assert run.returncode == code, (what, run.stdout + run.stderr)
        assert f"launch: {what} at" in run.stdout
        out = json.loads((tmp_path / f"run{i}" / "outcome.json").read_text())
        assert out["vehicles"]["AUV2"]["outcome"] == "done"
        assert out["vehicles"]["AUV1"]["outcome"] == (None if what == "time limit" else what)
    assert abs(out["sim_time_s"] - 20.0) < 0.2


def test_a_dying_process_stops_everything_with_its_own_code(tmp_path, lcm_url, child_env):
    veh = vehicle("AUV1", cycles=100000)
    veh["managers"][1]["bind"] = str(tmp_path / "bad.bind")
    (tmp_path / "bad.bind").write_text("input nav ${VEHICLE}.NAV gps_fix_t\n")  # gps_fix_t has no depth_m
    path = write_scenario(tmp_path, [veh])
    run = launch(path, tmp_path / "run", lcm_url, child_env)
    assert run.returncode == 5, run.stdout + run.stderr
    assert "AUV1.WATCHER" in run.stdout and "exited with status 1" in run.stdout
    assert not _alive(_pids_started(tmp_path / "run" / "run.lcmlog"))


def _pids_started(log_path):
    pids = []
    for ev in read_events(log_path):
        if ev.channel == "SIM.ANNOTATION" and ev.msg.name in ("start", "logger"):
            pids.append(int(ev.msg.text.split(" pid ")[1].split()[0].rstrip(":")))
    return pids


def _alive(pids):
    alive = []
    for pid in pids:
        try:
            with open(f"/proc/{pid}/stat") as f:
                if f.read().split(")")[-1].split()[0] != "Z":
                    alive.append(pid)
        except FileNotFoundError:
            pass
    return alive


def _wait_for_line(proc, text, timeout):
    deadline = time.monotonic() + timeout
    lines = []
    while time.monotonic() < deadline:
        line = proc.stdout.readline()
        lines.append(line)
        if text in line:
            return
        if not line and proc.poll() is not None:
            break
    raise AssertionError(f"no {text!r} in {lines}")


def _children(pid):
    try:
        return [int(p) for p in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except FileNotFoundError:
        return []


def test_sigint_stops_all_and_sigkill_of_the_launcher_orphans_nothing(tmp_path, lcm_url, child_env):
    path = write_scenario(tmp_path, [vehicle("AUV1", cycles=100000)], limit=100000)
    for sig, name in ((signal.SIGINT, "int"), (signal.SIGKILL, "kill")):
        out = tmp_path / name
        proc = subprocess.Popen(
            LAUNCH + [str(path), "--out", str(out), "--lcm-url", lcm_url, "--progress", "0.5"],
            env=child_env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        try:
            _wait_for_line(proc, "launch: t=", 90)  # running: the clock has started
            kids = _children(proc.pid)
            assert len(kids) == 4, kids  # logger, sim, 2 managers
            # lockstep: the world runs without wake-up preemption, the clock (the launcher)
            # keeps the default policy (tools/launch/sched_policy.py)
            assert {os.sched_getscheduler(p) for p in kids} == {os.SCHED_BATCH}
            assert os.sched_getscheduler(proc.pid) == os.SCHED_OTHER
            proc.send_signal(sig)
            rc = proc.wait(60)
        finally:
            if proc.poll() is None:
                proc.kill()
        deadline = time.monotonic() + 20
        while _alive(kids) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not _alive(kids), f"{name}: children left behind: {_alive(kids)}"
        log = load_log(out / "run.lcmlog")
        assert log.stats.undecodable == 0 and len(log["AUV1.TRUTH"]) > 10
        if sig == signal.SIGINT:
            assert rc == 130
            ends = [
                ev.msg.text
                for ev in read_events(out / "run.lcmlog")
                if ev.channel == "SIM.ANNOTATION" and ev.msg.name == "end"
            ]
            assert json.loads(ends[0])["outcome"] == "interrupted"
        else:
            assert rc == -signal.SIGKILL


def test_a_paced_world_or_sched_normal_keeps_the_default_scheduling(tmp_path, lcm_url, child_env):
    path = write_scenario(tmp_path, [vehicle("AUV1", cycles=100000)], limit=100000)
    for name, extra in (("realtime", ["--time", "realtime"]), ("normal", ["--sched", "normal"])):
        proc = subprocess.Popen(
            LAUNCH + [str(path), "--out", str(tmp_path / name), "--lcm-url", lcm_url, "--progress", "0.5", *extra],
            env=child_env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        try:
            _wait_for_line(proc, "launch: t=", 90)
            kids = _children(proc.pid)
            assert len(kids) == 4, kids
            assert {os.sched_getscheduler(p) for p in [proc.pid, *kids]} == {os.SCHED_OTHER}, name
            proc.send_signal(signal.SIGINT)
            assert proc.wait(60) == 130
        finally:
            if proc.poll() is None:
                proc.kill()


def test_host_split_runs_each_part_on_its_own(tmp_path, lcm_url, child_env):
    path = write_scenario(
        tmp_path, [vehicle("AUV1", host="alpha"), vehicle("AUV2", host="beta", cycles=80)], hosts=("alpha", "beta")
    )
    procs = [
        subprocess.Popen(
            LAUNCH + [str(path), "--host", h, "--out", str(tmp_path / "run"), "--lcm-url", lcm_url, "--progress", "0"],
            env=child_env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        for h in ("beta", "alpha")
    ]
    outs = [p.communicate(timeout=180)[0] for p in procs]
    assert [p.returncode for p in procs] == [0, 0], outs
    beta = json.loads((tmp_path / "run" / "outcome.beta.json").read_text())
    alpha = json.loads((tmp_path / "run" / "outcome.alpha.json").read_text())
    assert beta["log"] is None and alpha["log"]  # the logger runs on the first host only
    assert alpha["vehicles"]["AUV2"]["outcome"] == beta["vehicles"]["AUV1"]["outcome"] == "done"
    log = load_log(tmp_path / "run" / "run.lcmlog")
    assert len(log["AUV1.TRUTH"]) > 50 and len(log["AUV2.TRUTH"]) > 50
    assert "1 vehicle(s) on host alpha" in outs[1]
    assert "1 vehicle(s) on host beta" in outs[0]


def test_bad_scenarios_name_file_line_and_key(tmp_path, lcm_url, child_env):
    bad = tmp_path / "bad.yaml"
    bad.write_text(f"""name: bad
time:
  mode: fastest
  warp: -2
hosts: [a]
vehicles:
  - id: auv1
    host: b
    sim: {{config: {SIM}, initial: {{nort_m: 3}}}}
    managers:
      - {{name: NAVIGATOR, plan: missing.chasm, bind: {BIND}, rate: 10}}
      - {{name: NAVIGATOR, plan: {HERE / "watcher.chasm"}, bind: {BIND}, rat: 5}}
""")
    run = launch(bad, tmp_path / "run", lcm_url, child_env)
    assert run.returncode == 2
    err = run.stderr
    assert f"{bad}:3:9: time.mode: expected one of: realtime, scaled, lockstep" in err
    assert f"{bad}:4:9: time.warp: must be > 0" in err
    assert f"{bad}:7:9: vehicles[0].id: must be upper-case letters" in err
    assert f"{bad}:8:11: vehicles[0].host: unknown host 'b'" in err
    assert "vehicles[0].managers[0].plan: no such file" in err
    assert "vehicles[0].managers[1].rat: unknown key; did you mean 'rate'?" in err
    assert "manager name 'NAVIGATOR' used twice" in err

    sim_bad = write_scenario(tmp_path, [vehicle("AUV1")], name="simbad")
    text = sim_bad.read_text().replace("initial:", "initial:\n      nort_m: 3")
    sim_bad.write_text(text)
    line = next(i for i, ln in enumerate(text.splitlines(), 1) if "nort_m" in ln)
    run = launch(sim_bad, tmp_path / "run2", lcm_url, child_env)
    assert run.returncode == 2
    assert (
        f"{sim_bad}:{line}:15: vehicles[0].sim: initial.nort_m: unknown key; did you mean 'north_m'?" in run.stderr
    ), run.stderr

    plan_bad = write_scenario(tmp_path, [vehicle("AUV1", cycles="ten")], name="planbad")
    run = launch(plan_bad, tmp_path / "run3", lcm_url, child_env)
    assert run.returncode == 2 and "AUV1.NAVIGATOR: plan" in run.stderr and "mission.chasm:" in run.stderr
    assert not (tmp_path / "run3" / "run.lcmlog").exists()  # nothing started

    (tmp_path / "syntax.yaml").write_text("vehicles: [\n")
    run = launch(tmp_path / "syntax.yaml", tmp_path / "run4", lcm_url, child_env)
    assert run.returncode == 2 and f"{tmp_path / 'syntax.yaml'}:2:1: YAML syntax" in run.stderr


def test_bad_planned_faults_are_refused_before_anything_starts(tmp_path, lcm_url, child_env):
    sc = write_scenario(tmp_path, [vehicle("AUV1"), vehicle("AUV2", east=50)], name="faults")
    text = (
        sc.read_text()
        + """faults:
  - {at: 30, vehicle: AUV9, do: lose}
  - {at: 30, vehicle: AUV1, do: explode}
  - {at: 40, vehicle: AUV2, do: lose}
  - {at: 50, vehicle: AUV2}
  - {at: 500, vehicle: AUV1}
  - {vehicle: AUV1, when: 3}
  - lose AUV1
"""
    )
    sc.write_text(text)
    first = len(text.splitlines()) - 7 + 1  # line of the first entry
    run = launch(sc, tmp_path / "run", lcm_url, child_env)
    assert run.returncode == 2, run.stdout + run.stderr
    err = run.stderr
    assert f"{sc}:{first}:23: faults[0].vehicle: no vehicle 'AUV9' in this scenario; vehicles are: AUV1, AUV2" in err
    assert f"{sc}:{first + 1}:33: faults[1].do: expected one of: lose, leak, got 'explode'" in err
    assert f"{sc}:{first + 3}:23: faults[3].vehicle: AUV2 is already lost by the fault at {sc}:{first + 2}:5" in err
    assert f"{sc}:{first + 4}:10: faults[4].at: at 500 s is not before the mission time limit (60 s)" in err
    assert f"{sc}:{first + 5}:5: faults[5]: missing required key 'at'" in err
    assert f"{sc}:{first + 5}:21: faults[5].when: unknown key; expected one of: at, do, vehicle" in err
    assert f"{sc}:{first + 6}:5: faults[6]: expected a mapping" in err
    assert not (tmp_path / "run" / "run.lcmlog").exists()  # nothing started
    # host agents run the processes: a planned fault could not stop them (yet)
    sc.write_text(text.split("faults:")[0] + "faults:\n  - {at: 30, vehicle: AUV2}\n")
    run = launch(sc, tmp_path / "run", lcm_url, child_env, "--agents")
    assert run.returncode == 2 and "faults: not applied by host agents yet" in run.stderr, run.stderr


def test_lcm_logger_stays_selectable(tmp_path, lcm_url, child_env):
    """--recorder lcm-logger, or logging.recorder in the scenario; an unknown recorder is a scenario error."""
    path = write_scenario(tmp_path, [vehicle("AUV1", cycles=20)])
    run = launch(path, tmp_path / "run", lcm_url, child_env, "--recorder", "lcm-logger")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "recorder" not in json.loads((tmp_path / "run" / "outcome.json").read_text())
    notes = [
        ev.msg.text
        for ev in read_events(tmp_path / "run" / "run.lcmlog")
        if ev.channel == "SIM.ANNOTATION" and ev.msg.name == "logger"
    ]
    assert notes and notes[0].startswith("lcm-logger pid")
    # lcm-logger's 30-message queue loses much of a fast run on a loaded machine
    # (why auv-recorder is the default): only that it recorded the run is checked
    assert len(load_log(tmp_path / "run" / "run.lcmlog")["AUV1.TRUTH"]) > 0
    doc = yaml.safe_load(path.read_text())
    doc["logging"] = {"recorder": "tape"}
    path.write_text(yaml.safe_dump(doc))
    run = launch(path, tmp_path / "bad", lcm_url, child_env)
    assert run.returncode == 2 and "logging.recorder" in run.stderr and "auv-recorder, lcm-logger" in run.stderr

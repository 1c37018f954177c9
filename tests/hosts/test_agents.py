"""Host agents over real LCM with real processes (docs/hosts.md): two agents
("hosts" alpha and beta on one machine, each its own agent), a scenario sent
by agentctl, restarts per policy with back-off and a limit, stop, refusals,
the dead-man time, and an agent's death taking its processes with it."""

from __future__ import annotations

import os
import signal
import time

import numpy as np
import pytest
from agents import AgentProc, Tables, alive, ctl, vehicle, wait_until, write_scenario

from auv import agent_ack_t, agent_command_t
from auv import agent_process_t as P

# a mission that outlasts the test: only the test ends it (fast time would reach a time limit)
ENDLESS = {"mode": "realtime", "limit": 3600, "wall_limit": 600}
RUNNING, BACKOFF, FAILED, STOPPED = P.STATE_RUNNING, P.STATE_BACKOFF, P.STATE_FAILED, P.STATE_STOPPED


@pytest.fixture
def two_agents(tmp_path, lcm_url, child_env):
    agents = [AgentProc(h, lcm_url, tmp_path / "agents", child_env) for h in ("alpha", "beta")]
    tables = Tables(lcm_url, ["alpha", "beta"])
    try:
        wait_until(lambda: tables.latest("alpha") and tables.latest("beta"), 30, "both agents publish a table")
        yield agents, tables
    finally:
        tables.close()
        for a in agents:
            a.stop()


def running(tables, host, names):
    rows = tables.rows(host)
    return all(n in rows and rows[n].state == RUNNING and rows[n].pid > 0 for n in names) and rows


def test_scenario_split_restart_with_backoff_and_limit_then_stop(tmp_path, lcm_url, child_env, two_agents):
    agents, tables = two_agents
    sc = write_scenario(
        tmp_path / "pair.yaml", [vehicle("AUV1", "alpha"), vehicle("AUV2", "beta", east=40)], ["alpha", "beta"]
    )
    run = ctl(
        lcm_url, child_env, "start", str(sc), "--restart", "AUV1.NAVIGATOR=on-failure:2:0.5:5", "--restart", "*=never"
    )
    assert run.returncode == 0, run.stdout + run.stderr
    assert "alpha: ok: started 4 process(es) of 'pair': logger, AUV1.sim, AUV1.NAVIGATOR, AUV1.WATCHER" in run.stdout
    assert "beta: ok: started 3 process(es)" in run.stdout  # the logger runs on the first host only
    # agentctl has ended (a launcher gone): the parts keep running on their own
    a = wait_until(
        lambda: running(tables, "alpha", ["logger", "AUV1.sim", "AUV1.NAVIGATOR", "AUV1.WATCHER"]),
        30,
        "alpha's part running",
    )
    b = wait_until(
        lambda: running(tables, "beta", ["AUV2.sim", "AUV2.NAVIGATOR", "AUV2.WATCHER"]), 30, "beta's part running"
    )
    assert set(b) == {"AUV2.sim", "AUV2.NAVIGATOR", "AUV2.WATCHER"}
    wait_until(lambda: tables.rows("alpha")["AUV1.sim"].rss_bytes > 10 << 20, 10, "memory read from /proc")
    wait_until(lambda: tables.rows("alpha")["AUV1.sim"].cpu_load > 0, 20, "CPU read from /proc")
    pids = {n: r.pid for n, r in {**a, **b}.items()}

    # the NAVIGATOR dies: restarted after 0.5 s, then after 1 s (doubled), then the limit (2) holds
    seen_pids = [pids["AUV1.NAVIGATOR"]]
    for n, wait_s in ((1, 0.5), (2, 1.0)):
        killed_at = time.monotonic()
        os.kill(seen_pids[-1], signal.SIGKILL)
        wait_until(lambda: tables.rows("alpha")["AUV1.NAVIGATOR"].state == BACKOFF, 10, "back-off shown")
        row = wait_until(
            lambda: (r := tables.rows("alpha")["AUV1.NAVIGATOR"]).state == RUNNING and r.restarts == n and r,
            20,
            f"restart {n}",
        )
        assert row.pid not in seen_pids and row.exit_code == -signal.SIGKILL
        restarted_at = next(
            t
            for t, tb in tables.history["alpha"]
            if any(p.name == "AUV1.NAVIGATOR" and p.restarts == n for p in tb.procs)
        )
        assert restarted_at - killed_at >= wait_s  # never before its back-off
        seen_pids.append(row.pid)
    os.kill(seen_pids[-1], signal.SIGKILL)
    row = wait_until(lambda: (r := tables.rows("alpha")["AUV1.NAVIGATOR"]).state == FAILED and r, 10, "limit")
    assert row.restarts == 2 and row.pid == -1
    # policy never: a WATCHER that dies stays dead, and the rest carry on
    os.kill(pids["AUV2.WATCHER"], signal.SIGKILL)
    row = wait_until(lambda: (r := tables.rows("beta")["AUV2.WATCHER"]).state == FAILED and r, 10, "never")
    assert row.restarts == 0
    assert running(tables, "beta", ["AUV2.sim", "AUV2.NAVIGATOR"])

    stop = ctl(lcm_url, child_env, "stop", str(sc))
    assert stop.returncode == 0, stop.stdout + stop.stderr
    assert "alpha: ok: stopped 3 process(es)" in stop.stdout and "beta: ok: stopped 2 process(es)" in stop.stdout
    for h in ("alpha", "beta"):
        assert all(p.state in (STOPPED, FAILED) for p in tables.rows(h).values())
    for pid in list(pids.values()) + seen_pids:  # nothing left behind
        assert not alive(pid), pid
    assert (tmp_path / "agents" / "alpha" / "pair" / "run.lcmlog").exists()
    status = ctl(lcm_url, child_env, "status", "--host", "alpha", "--host", "beta")
    assert status.returncode == 0 and "AUV1.NAVIGATOR" in status.stdout and "failed" in status.stdout


def command(host: str, kind: int, seq: int, **f) -> agent_command_t:
    c = agent_command_t()
    c.utime, c.host, c.sender, c.seq, c.command = 1, host, "test", seq, kind
    c.run, c.scenario_path, c.scenario_text = f.get("run", ""), f.get("path", ""), f.get("text", "")
    c.deadman_s, c.restart, c.n_restart = f.get("deadman_s", 0.0), [], 0
    return c


def ack_for(tables, host, seq):
    return wait_until(
        lambda: next((a for a in list(tables.acks) if a.host == host and a.seq == seq and a.sender == "test"), None),
        30,
        f"ack {seq} from {host}",
    )


def test_refusals_change_nothing_and_say_why(tmp_path, lcm_url, child_env, two_agents, capsys):
    from tools.hosts import agentctl

    agents, tables = two_agents
    good = write_scenario(tmp_path / "one.yaml", [vehicle("AUV1", "alpha")], ["alpha", "beta"])
    # a command for beta on alpha's channel
    tables.publish(
        "AGENT.alpha.CMD", command("beta", agent_command_t.CMD_START, 1, path=str(good), text=good.read_text())
    )
    a = ack_for(tables, "alpha", 1)
    assert a.result == agent_ack_t.RESULT_REJECTED and "host 'beta'" in a.message and "'alpha'" in a.message
    # a bad scenario: every error with file:line:col, nothing started
    bad = tmp_path / "bad.yaml"
    bad.write_text(good.read_text().replace("host: alpha", "host: gamma").replace("seed:", "sede:"))
    tables.publish(
        "AGENT.alpha.CMD", command("alpha", agent_command_t.CMD_START, 2, path=str(bad), text=bad.read_text())
    )
    a = ack_for(tables, "alpha", 2)
    assert a.result == agent_ack_t.RESULT_REJECTED
    assert f"{bad}:2:1: sede: unknown key; did you mean 'seed'?" in a.message  # the sender's path
    assert "unknown host 'gamma'" in a.message
    # a host the scenario does not have
    three = write_scenario(tmp_path / "three.yaml", [vehicle("AUV1", "gamma")], ["gamma"])
    run = ctl(lcm_url, child_env, "start", str(three), "--host", "alpha")  # checked here first
    assert run.returncode == 2 and "--host alpha: not among the scenario's hosts: gamma" in run.stderr
    tables.publish(
        "AGENT.beta.CMD", command("beta", agent_command_t.CMD_START, 3, path=str(three), text=three.read_text())
    )
    a = ack_for(tables, "beta", 3)
    assert a.result == agent_ack_t.RESULT_REJECTED and "'beta' is not one of: gamma" in a.message
    assert tables.latest("alpha").procs == [] and tables.latest("beta").procs == []
    # a bad restart rule and a bad dead-man time never leave agentctl
    for bad_args in (
        ["--restart", "*=sometimes"],
        ["--restart", "*=on-failure:x"],
        ["--deadman", "-1"],
        ["--restart", "*=on-failure:1:nan"],
    ):
        assert agentctl.main(["start", str(good), "--lcm-url", lcm_url, *bad_args]) == 2
        err = capsys.readouterr().err
        assert err.startswith("agentctl: ") and "Traceback" not in err, err

    # garbage on the command channel is counted and dropped; bad restart rules in a raw command are refused
    class Raw:
        def __init__(self, data):
            self.data = data

        def encode(self):
            return self.data

    tables.publish("AGENT.alpha.CMD", Raw(b"\x00" * 7))
    tables.publish("AGENT.alpha.CMD", Raw(command("alpha", agent_command_t.CMD_STOP, 99).encode()[:-3]))
    from auv import agent_restart_t

    rules = []
    for pattern, policy, limit, backoff in (
        ("", 1, 1, 1.0),
        ("*", 7, 1, 1.0),
        ("*", 1, -1, 1.0),
        ("*", 1, 1, float("nan")),
        ("*", 1, 1, -2.0),
    ):
        r = agent_restart_t()
        r.process, r.policy, r.max_restarts, r.backoff_s, r.backoff_max_s = pattern, policy, limit, backoff, 1.0
        rules.append(r)
    raw = command("alpha", agent_command_t.CMD_START, 5, path=str(good), text=good.read_text(), deadman_s=-1.0)
    raw.restart, raw.n_restart = rules, len(rules)
    tables.publish("AGENT.alpha.CMD", raw)
    a = ack_for(tables, "alpha", 5)
    assert a.result == agent_ack_t.RESULT_REJECTED and len(a.message.splitlines()) == 6, a.message
    for needle in (
        "empty process pattern",
        "policy 7",
        "max_restarts -1",
        "backoff_s nan",
        "backoff_s -2.0",
        "deadman_s -1.0",
    ):
        assert needle in a.message, needle
    assert "lcm_rx: AGENT.alpha.CMD: dropped" in agents[0].text()
    # a second START while running is refused; a resent START is answered, not run twice
    start = command("alpha", agent_command_t.CMD_START, 4, path=str(good), text=good.read_text())
    tables.publish("AGENT.alpha.CMD", start)
    assert ack_for(tables, "alpha", 4).result == agent_ack_t.RESULT_OK
    tables.publish("AGENT.alpha.CMD", start)
    run = ctl(lcm_url, child_env, "start", str(good), "--host", "alpha")
    assert run.returncode == 3 and "alpha: refused: already running 'one'" in run.stderr
    assert len([a for a in tables.acks if a.seq == 4]) == 2
    assert agents[0].text().count("START from test seq 4") == 1
    # no agent for a host: no answer, exit 4
    run = ctl(lcm_url, child_env, "stop", "--host", "nobody", "--timeout", "2")
    assert run.returncode == 4 and "nobody: no answer" in run.stderr
    assert ctl(lcm_url, child_env, "stop", "--host", "alpha").returncode == 0
    # SIGTERM ends an agent cleanly
    assert agents[0].stop() == 0 and "Traceback" not in agents[0].text(), agents[0].text()


def test_deadman_stops_a_run_whose_launcher_went_silent(tmp_path, lcm_url, child_env, two_agents):
    agents, tables = two_agents
    sc = write_scenario(tmp_path / "dm.yaml", [vehicle("AUV1", "beta")], ["alpha", "beta"])
    run = ctl(lcm_url, child_env, "start", str(sc), "--deadman", "3")
    assert run.returncode == 0, run.stderr
    assert "alpha: ok: started 1 process(es) of 'dm': logger" in run.stdout  # the log host is the first
    rows = wait_until(lambda: running(tables, "beta", ["AUV1.sim", "AUV1.NAVIGATOR"]), 30, "beta running")
    # silence (agentctl has ended): the run stops by itself (keepalives that hold a run:
    # test_a_killed_agent_launcher_leaves_its_parts_to_the_deadman)
    t = wait_until(lambda: (t := tables.latest("beta")).status.startswith("stopped") and t, 30, "dead-man")
    assert "dead-man" in t.status and all(p.state == STOPPED for p in t.procs)
    assert not any(alive(r.pid) for r in rows.values())


def test_a_dead_agent_leaves_no_process_and_a_new_one_starts_clean(tmp_path, lcm_url, child_env, two_agents):
    agents, tables = two_agents
    sc = write_scenario(tmp_path / "solo.yaml", [vehicle("AUV1", "alpha")], ["alpha"], logging={"enabled": False})
    assert ctl(lcm_url, child_env, "start", str(sc)).returncode == 0
    rows = wait_until(lambda: running(tables, "alpha", ["AUV1.sim", "AUV1.NAVIGATOR", "AUV1.WATCHER"]), 30, "up")
    agents[0].stop(signal.SIGKILL)
    wait_until(lambda: not any(alive(r.pid) for r in rows.values()), 15, "children gone with their agent")
    again = AgentProc("alpha", lcm_url, tmp_path / "agents2", child_env)
    try:
        wait_until(
            lambda: (t := tables.latest("alpha")) and t.agent_pid == again.p.pid and t.run == "",
            30,
            "the new agent idle",
        )
        status = ctl(lcm_url, child_env, "status", "--host", "alpha", "--json")
        assert status.returncode == 0 and '"run": ""' in status.stdout
    finally:
        again.stop()


def test_launch_through_agents_runs_the_mission_on_its_clock(tmp_path, lcm_url, child_env, two_agents):
    import json
    import subprocess
    import sys

    agents, tables = two_agents
    sc = write_scenario(
        tmp_path / "via.yaml",
        [vehicle("AUV1", "alpha"), vehicle("AUV2", "beta", east=40, cycles=80)],
        ["alpha", "beta"],
    )
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "tools.launch",
            str(sc),
            "--agents",
            "--out",
            str(tmp_path / "run"),
            "--lcm-url",
            lcm_url,
            "--progress",
            "0",
        ],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    out = json.loads((tmp_path / "run" / "outcome.json").read_text())
    assert out["outcome"] == "done" and {v["outcome"] for v in out["vehicles"].values()} == {"done"}
    for h in ("alpha", "beta"):  # every part stopped at the end
        t = wait_until(lambda: (t := tables.latest(h)).status.startswith("stopped") and t, 20, f"{h} stopped")
        assert t.procs and all(p.state == STOPPED for p in t.procs)
    assert "alpha: ok: started 4 process(es)" in run.stdout and "beta: ok: stopped 3 process(es)" in run.stdout
    log = tmp_path / "agents" / "alpha" / "via" / "run.lcmlog"  # recorded by alpha's agent
    from auvlcm.arrays import load_log

    arrays = load_log(log, keep_messages=r"SIM\.(ANNOTATION|LOCKSTEP)")
    assert len(arrays["AUV2.TRUTH"]) > 50
    # the agent records with auv-recorder, a participant of the lockstep world
    # (the clock on the launcher's host waited for it): nothing lost, no gap
    for vid in ("AUV1", "AUV2"):
        steps = np.diff(arrays[f"{vid}.TRUTH"].columns["utime"])
        assert steps.size and np.all(steps == steps[0]), (vid, sorted(set(steps.tolist())))
    counts = json.loads((log.parent / "recorder.json").read_text())
    assert counts["dropped"] == 0 and counts["missed"] == 0 and counts["written"] == counts["received"], counts
    reporters = {m.participant for m in arrays.messages["SIM.LOCKSTEP"]}
    assert "SIM.RECORDER" in reporters, reporters
    assert any(n.name == "end" for n in arrays.messages["SIM.ANNOTATION"])


def test_a_killed_agent_launcher_leaves_its_parts_to_the_deadman(tmp_path, lcm_url, child_env, two_agents):
    import subprocess
    import sys

    agents, tables = two_agents
    sc = write_scenario(
        tmp_path / "long.yaml", [vehicle("AUV1", "beta", cycles=100000)], ["alpha", "beta"], time=ENDLESS
    )
    launcher = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "tools.launch",
            str(sc),
            "--agents",
            "--deadman",
            "3",
            "--out",
            str(tmp_path / "run"),
            "--lcm-url",
            lcm_url,
            "--progress",
            "0",
        ],
        env=child_env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        rows = wait_until(lambda: running(tables, "beta", ["AUV1.sim", "AUV1.NAVIGATOR"]), 60, "parts running")
        time.sleep(4.0)  # longer than the dead-man time: the keepalives hold the run
        assert running(tables, "beta", ["AUV1.sim", "AUV1.NAVIGATOR"]), tables.latest("beta").status
    finally:
        launcher.kill()
        launcher.wait()
    t = wait_until(lambda: (t := tables.latest("beta")).status.startswith("stopped") and t, 30, "dead-man")
    assert "dead-man" in t.status and not any(alive(r.pid) for r in rows.values())
    assert agents[1].p.poll() is None  # the agent itself lives on


def test_an_agent_launcher_outlives_a_dead_agent_and_says_so(tmp_path, lcm_url, child_env, two_agents):
    import subprocess
    import sys

    agents, tables = two_agents
    sc = write_scenario(
        tmp_path / "lost.yaml",
        [vehicle("AUV1", "alpha", cycles=100000), vehicle("AUV2", "beta", cycles=100000)],
        ["alpha", "beta"],
        time=ENDLESS,
    )
    launcher = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "tools.launch",
            str(sc),
            "--agents",
            "--agent-timeout",
            "5",
            "--out",
            str(tmp_path / "run"),
            "--lcm-url",
            lcm_url,
            "--progress",
            "0",
        ],
        env=child_env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    try:
        wait_until(lambda: running(tables, "beta", ["AUV2.sim", "AUV2.NAVIGATOR"]), 60, "parts running")
        agents[1].stop(signal.SIGKILL)
        out = launcher.communicate(timeout=60)[0]
    finally:
        if launcher.poll() is None:
            launcher.kill()
    assert launcher.returncode == 5, out
    assert "the agent of host beta is silent for 5 s" in out
    assert "alpha: ok: stopped" in out and "beta: no answer" in out  # the rest stopped all the same
    assert all(p.state == STOPPED for p in tables.latest("alpha").procs)


def test_launch_through_agents_refuses_another_recorder_than_the_scenarios(tmp_path, lcm_url, child_env):
    """With --agents the log host's agent records with the scenario's
    logging.recorder: a --recorder that says otherwise is refused before any
    agent is asked (no agent runs here: none is needed to refuse)."""
    import subprocess
    import sys

    sc = write_scenario(tmp_path / "rec.yaml", [vehicle("AUV1", "alpha")], ["alpha"])
    argv = [sys.executable, "-m", "tools.launch", str(sc), "--agents", "--out", str(tmp_path / "run")]
    run = subprocess.run(
        [*argv, "--lcm-url", lcm_url, "--recorder", "lcm-logger"],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.returncode == 2, run.stdout + run.stderr
    assert "--recorder lcm-logger" in run.stderr and "logging.recorder (auv-recorder)" in run.stderr, run.stderr

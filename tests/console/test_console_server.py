"""The console's model, layers and server without a browser: the state a page
gets over the event stream, a command to a real chasm-manager and its ack, a
log opened with seeks, and the refusals."""

from __future__ import annotations

import http.client
import json
import time
from urllib.parse import urlparse

import pytest
import yaml
from conftest import ROOT
from console_fixtures import Console, write_run_log
from manager_world import ManagerWorld

from tools.console.model import Model, Series, Trail
from tools.console.world import WorldBuilder, WorldError


class Page:
    """What a browser does: read the event stream, post commands."""

    def __init__(self, url: str) -> None:
        u = urlparse(url)
        self.host, self.port = u.hostname, u.port
        self.conn = http.client.HTTPConnection(self.host, self.port, timeout=30)
        self.conn.request("GET", "/api/events")
        self.stream = self.conn.getresponse()
        assert self.stream.status == 200 and self.stream.getheader("Content-Type") == "text/event-stream"
        self.world = None
        self.series: dict[str, list] = {}

    def next(self) -> dict:
        while True:
            line = self.stream.readline()
            assert line, "the event stream ended"
            if line.startswith(b"data: "):
                d = json.loads(line[6:])
                self.world = d.get("world", self.world)
                for name, part in d["series"].items():
                    if part["reset"]:
                        self.series[name] = []
                    self.series.setdefault(name, []).extend(part["add"])
                return d["now"]

    def until(self, pred, timeout: float = 20.0, what: str = "") -> dict:
        deadline = time.monotonic() + timeout
        now = None
        while time.monotonic() < deadline:
            now = self.next()
            if pred(now):
                return now
        raise AssertionError(f"{what}: not seen in {timeout} s; last {json.dumps(now)[:600]}")

    def post(self, path: str, body, headers: dict | None = None) -> tuple[int, dict]:
        conn = http.client.HTTPConnection(self.host, self.port, timeout=10)
        conn.request(
            "POST",
            path,
            body=body if isinstance(body, bytes) else json.dumps(body).encode(),
            headers=headers or {"Content-Type": "application/json"},
        )
        r = conn.getresponse()
        return r.status, json.loads(r.read())

    def get(self, path: str) -> tuple[int, bytes]:
        conn = http.client.HTTPConnection(self.host, self.port, timeout=10)
        conn.request("GET", path)
        r = conn.getresponse()
        return r.status, r.read()


def test_series_give_each_reader_what_is_new_and_reset_a_reader_left_behind():
    s = Series(limit=20)
    for i in range(15):
        s.append(i)
    assert s.since(0) == (False, list(range(15)))
    assert s.since(10) == (False, [10, 11, 12, 13, 14])
    for i in range(15, 30):
        s.append(i)
    reset, items = s.since(3)  # 3 was dropped: the reader starts over
    assert reset and items == s.items and items[-1] == 29 and len(items) <= 20
    assert s.since(s.end) == (False, [])
    t = Trail(min_step_m=1.0)
    for e in (0.0, 0.3, 0.9, 1.2, 1.5, 2.4):
        t.add(0.0, e)
    assert [p[1] for p in t.items] == [0.0, 1.2, 2.4]


def test_layers_come_from_the_scenario_with_its_survey_and_seabed():
    model = Model()
    world = WorldBuilder(model)
    scenario = ROOT / "missions" / "scenarios" / "mcm_demo" / "mcm_demo.yaml"
    world.load_scenario(scenario)
    w = model.world
    assert len(w["survey_area"]) == 5 and len(w["operating_area"]) > 10
    assert set(w["lines"]) == {"AUV1", "AUV2", "AUV3"} and all(len(v) >= 3 for v in w["lines"].values())
    assert [t["id"] for t in w["transponders"]] == [1, 2, 3]
    sb = w["seabed"]
    n, e = sb["north0"] + 0.5 * sb["dn"], sb["east0"] + 0.5 * sb["de"]
    spec = yaml.safe_load(scenario.read_text())["world"]["bathymetry"]  # slope:depth=D,dn=A,de=B
    assert spec.startswith("slope:")
    k = {key: float(v) for key, v in (kv.split("=") for kv in spec[len("slope:") :].split(","))}
    assert sb["depth"][0][0] == pytest.approx(k["depth"] + k["dn"] * n + k["de"] * e, abs=0.01)


def test_a_bad_scenario_is_a_clear_error(tmp_path, child_env):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\nsurvey: missing.json\n")
    with pytest.raises(WorldError, match="missing.json"):
        WorldBuilder(Model()).load_scenario(bad)
    import subprocess
    import sys

    run = subprocess.run(
        [sys.executable, "-m", "tools.console", "--scenario", str(bad), "--port", "0"],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert run.returncode == 2 and "missing.json" in run.stderr and "Traceback" not in run.stderr


def test_the_page_sees_a_real_manager_and_a_pause_round_trips(lcm_url, child_env):
    world = ManagerWorld(lcm_url, child_env)
    console = Console(["--lcm-url", lcm_url], child_env)
    try:
        page = Page(console.url)
        now = page.until(
            lambda n: n["vehicles"].get("AUV1", {}).get("managers", {}).get("NAVIGATOR"), what="AUV1 NAVIGATOR"
        )
        nav = now["vehicles"]["AUV1"]["managers"]["NAVIGATOR"]
        assert nav["run"] == "running" and nav["path"] == "dive" and nav["plan"].endswith("dive.chasm")
        page.until(lambda n: n["vehicles"]["AUV1"]["nav"], what="AUV1 nav")
        assert page.series["AUV1.nav"][0] == [10.0, 5.0]

        status, body = page.post("/api/command", {"vehicle": "AUV1", "manager": "NAVIGATOR", "command": "pause"})
        assert status == 200, body
        seq = body["seq"]
        now = page.until(lambda n: any(a["seq"] == seq for a in n["vehicles"]["AUV1"]["acks"]), what="the ack")
        ack = next(a for a in now["vehicles"]["AUV1"]["acks"] if a["seq"] == seq)
        assert ack == {"seq": seq, "manager": "NAVIGATOR", "message": "paused", "result": "ok"}
        page.until(lambda n: n["vehicles"]["AUV1"]["managers"]["NAVIGATOR"]["run"] == "paused", what="paused")

        # load a plan: its text travels in the command, the manager answers
        from manager_world import HERE

        status, body = page.post(
            "/api/command",
            {
                "vehicle": "AUV1",
                "manager": "NAVIGATOR",
                "command": "load",
                "plan_name": "again.chasm",
                "plan_text": (HERE / "dive.chasm").read_text(),
            },
        )
        assert status == 200, body
        now = page.until(
            lambda n: any(a["seq"] == body["seq"] for a in n["vehicles"]["AUV1"]["acks"]), what="the load ack"
        )
        ack = next(a for a in now["vehicles"]["AUV1"]["acks"] if a["seq"] == body["seq"])
        assert (ack["result"], ack["message"]) == ("ok", "plan loaded")

        # refusals: a clear error each, nothing published
        assert page.post("/api/command", {"vehicle": "AUV1", "command": "explode"})[0] == 400
        assert page.post("/api/command", {"vehicle": "AUV1", "command": "load"})[0] == 400  # no plan text
        assert page.post("/api/command", b"not json")[0] == 400
        assert page.post("/api/seek", {"t": 3})[0] == 409
        # another web site open in the operator's browser cannot command the vehicles
        pause = {"vehicle": "AUV1", "command": "abort"}
        assert page.post("/api/command", pause, {"Content-Type": "text/plain"})[0] == 415
        assert (
            page.post("/api/command", pause, {"Content-Type": "application/json", "Origin": "http://evil.example"})[0]
            == 403
        )
        assert (
            page.post(
                "/api/command", pause, {"Content-Type": "application/json", "Origin": f"http://{page.host}:{page.port}"}
            )[0]
            == 200
        )
        assert page.get("/static/../server.py")[0] == 404
        assert page.get("/nothing")[0] == 404
        status, html = page.get("/")
        assert status == 200 and b"console.js" in html and b"http" not in html.replace(b"http-equiv", b"")
    finally:
        assert console.stop() == 0
        assert world.close() == 0


def test_lcm_logplayer_replay_shows_like_live(tmp_path, lcm_url, child_env):
    import subprocess

    from lcm_proc import lcm_tool

    write_run_log(tmp_path / "r.lcmlog")
    console = Console(["--lcm-url", lcm_url], child_env)
    player = None
    try:
        page = Page(console.url)
        player = subprocess.Popen(
            [lcm_tool("lcm-logplayer"), f"--lcm-url={lcm_url}", "--speed=1", str(tmp_path / "r.lcmlog")],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        now = page.until(
            lambda n: n["vehicles"].get("AUV2", {}).get("managers", {}).get("NAVIGATOR", {}).get("run") == "aborted",
            timeout=30,
            what="AUV2 aborted in the replay",
        )
        assert sorted(now["vehicles"]) == ["AUV1", "AUV2"]
        assert now["vehicles"]["AUV2"]["managers"]["NAVIGATOR"]["path"] == "emergency"
        assert len(page.series["AUV1.true"]) > 10 and page.series["contacts"][0]["class"] == "mine_like"
    finally:
        if player:
            player.wait(timeout=30)
        assert console.stop() == 0


def test_a_finished_log_opens_with_seeks_forward_and_back(tmp_path, child_env):
    write_run_log(tmp_path / "r.lcmlog")
    console = Console(["--log", str(tmp_path / "r.lcmlog")], child_env)
    try:
        page = Page(console.url)
        status, info = page.get("/api/info")
        info = json.loads(info)
        assert info["mode"] == "log" and info["start"] == 0.0 and abs(info["end"] - 5.9) < 1e-6
        now = page.until(lambda n: n["t"] == info["end"], what="the end of the log")
        assert now["vehicles"]["AUV2"]["managers"]["NAVIGATOR"]["run"] == "aborted"
        assert len(page.series["AUV1.true"]) == 60 and len(page.series["contacts"]) == 1
        assert page.post("/api/seek", {"t": 2.0}) == (200, {"t": 2.0})  # back: the model starts over
        now = page.until(lambda n: n["t"] == 2.0, what="t = 2 s")
        assert now["vehicles"]["AUV2"]["managers"]["NAVIGATOR"]["run"] == "running"
        assert len(page.series["AUV1.true"]) == 21 and page.series.get("contacts", []) == []
        assert now["vehicles"]["AUV1"]["truth"]["n"] == 20.0
        fs = now["vehicles"]["AUV1"]["frontseat"]
        assert (fs["control"], fs["state"], fs["mode"], fs["granted"]) == ("payload", "payload", "A", 1), fs
        assert now["vehicles"]["AUV2"]["frontseat"] is None  # a vehicle with our own pilot
        assert page.post("/api/seek", {"t": 3.05})[1] == {"t": 3.05}  # forward: only what is new
        now = page.until(lambda n: n["t"] == 3.05, what="t = 3.05 s")
        assert len(page.series["AUV1.true"]) == 31 and len(page.series["contacts"]) == 1
        assert [ln["src"] for ln in now["links"]] == ["AUV1"]
        fs = now["vehicles"]["AUV1"]["frontseat"]
        assert (fs["control"], fs["state"], fs["lost"]) == ("operator", "manual", 1), fs
        assert page.post("/api/seek", {"t": 1e9})[1] == {"t": info["end"]}  # clamped
        assert page.post("/api/seek", {"t": "soon"})[0] == 400
        assert page.post("/api/command", {"vehicle": "AUV1", "command": "pause"})[0] == 409
    finally:
        assert console.stop() == 0


def test_the_model_keeps_each_agents_process_table_and_its_wall_stamp_moves_no_time():
    from auv import agent_process_t, agent_table_t, sim_clock_t

    m = Model()
    c = sim_clock_t()
    c.utime, c.server_id, c.mode = 12_000_000, "launcher", sim_clock_t.MODE_LOCKSTEP
    m.apply("SIM.CLOCK", c)
    t = agent_table_t()
    t.utime, t.host, t.agent_pid, t.run, t.status, t.launcher_silent_s = (
        1_790_000_000_000_000,
        "alpha",
        41,
        "mcm",
        "running",
        0.7,
    )
    procs = []
    for name, state, code in (
        ("AUV1.sim", agent_process_t.STATE_RUNNING, 0),
        ("AUV1.PILOT", agent_process_t.STATE_BACKOFF, -9),
    ):
        p = agent_process_t()
        p.name, p.pid, p.state, p.exit_code, p.restarts, p.cpu_load, p.rss_bytes, p.uptime_s = (
            name,
            100 + len(procs),
            state,
            code,
            len(procs),
            0.25,
            50_000_000,
            30.0,
        )
        procs.append(p)
    t.procs, t.n_procs = procs, len(procs)
    assert m.apply("AGENT.alpha.PROCS", t)
    with m.lock:
        now = json.loads(m.now_json())
    assert now["t"] == 12.0  # the host's wall clock is not the world's time
    a = now["agents"]["alpha"]
    assert (a["status"], a["run"], a["pid"]) == ("running", "mcm", 41)
    assert [(p["name"], p["state"], p["exit_code"], p["restarts"]) for p in a["procs"]] == [
        ("AUV1.sim", "running", 0, 0),
        ("AUV1.PILOT", "back-off", -9, 1),
    ]
    assert a["procs"][0]["rss_mb"] == 50.0 and a["procs"][0]["cpu"] == 0.25


def test_the_page_shows_a_live_agents_table(lcm_url, child_env):
    import subprocess
    import sys

    agent = subprocess.Popen(
        [sys.executable, "-m", "tools.hosts.agent", "--host", "alpha", "--lcm-url", lcm_url],
        env=child_env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    console = Console(["--lcm-url", lcm_url], child_env)
    try:
        page = Page(console.url)
        now = page.until(lambda n: "alpha" in n.get("agents", {}), what="the agent of host alpha")
        a = now["agents"]["alpha"]
        assert a["status"] == "idle" and a["pid"] == agent.pid and a["procs"] == [], a
    finally:
        console.stop()
        agent.terminate()
        agent.wait(timeout=10)

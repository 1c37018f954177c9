"""A hostile corpus of configuration files and scenarios: every one ends in
`file:line:col: message` lines, exit status 2 and no traceback, fast, from
the launcher (scenarios), auv-navconf and the simulator (sim configs)."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest
from conftest import ROOT

from confcheck import ConfigError

HERE = ROOT / "tests" / "tools" / "scenarios"
SIM = ROOT / "missions" / "sim" / "remus100_multihil.yaml"
LAUNCH = [sys.executable, "-m", "tools.launch"]
NAVCONF = [sys.executable, "-m", "tools.nav.navconf"]
BOMB = (
    b"a: &a [x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
    b"c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b]\nd: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c]\n"
    b"e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d]\nf: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e]\n"
    b"g: &g [*f, *f, *f, *f, *f, *f, *f, *f, *f]\nh: &h [*g, *g, *g, *g, *g, *g, *g, *g, *g]\n"
    b"i: &i [*h, *h, *h, *h, *h, *h, *h, *h, *h]\n"
)

# name: (file bytes, what the error must say, line:col)
FILES = {
    "empty": (b"", "empty file", "1:1"),
    "only comments": (b"# nothing\n\n", "empty file", "1:1"),
    "nested 5000": (b"[" * 5000, "nested deeper than 32 levels", "1:33"),
    "nested maps": (b"a:\n" + b"".join(b" " * i + b"b:\n" for i in range(1, 60)), "nested deeper", ""),
    "alias bomb": (BOMB, "anchor '&a' refused", "1:4"),
    "alias": (b"vehicles: *v\n", "alias '*v' refused", "1:11"),
    "anchor": (b"vehicles: &v []\n", "anchor '&v' refused", "1:11"),
    "invalid utf-8": (b"name: ok\nvehicles:\n  - id: AUV\xff1\n", "not UTF-8 (byte 0xff)", "3:12"),
    "control char": (b"name: a\x07b\n", "not allowed in YAML", "1:8"),
    "python tag": (b"name: !!python/object:os.system x\n", "tag", "1:7"),
    "not a mapping": (b"- a\n- b\n", "expected a mapping", "1:1"),
    "huge": (b"#" + b"x" * (256 << 10) + b"\n", "larger than 262144 (the limit)", ""),
    "many values": (b"a: [" + b"1, " * 10001 + b"1]\n", "more than 10000 values (the limit)", "1:"),
}


@pytest.mark.parametrize("name", sorted(FILES))
def test_hostile_scenario_files_give_file_line_col_and_exit_2(tmp_path, name):
    data, what, pos = FILES[name]
    path = tmp_path / "bad.yaml"
    path.write_bytes(data)
    t0 = time.monotonic()
    run = subprocess.run(
        LAUNCH + [str(path), "--out", str(tmp_path / "run")], capture_output=True, text=True, timeout=60
    )
    assert time.monotonic() - t0 < 30
    assert run.returncode == 2 and "Traceback" not in run.stderr, run.stderr
    assert what in run.stderr and f"{path}:{pos}" in run.stderr, run.stderr
    run = subprocess.run(NAVCONF + [str(path)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and "Traceback" not in run.stderr and what in run.stderr, run.stderr


def _scenario(tmp_path, vehicle_extra="", manager_extra="", vid="AUV1"):
    path = tmp_path / "s.yaml"
    path.write_text(f"""name: hostile
time: {{mode: lockstep, limit: 10}}
vehicles:
  - id: {vid}
    sim: {{config: {SIM}}}
    managers:
      - name: NAVIGATOR
        plan: {HERE / "mission.chasm"}
        bind: {ROOT / "missions" / "bindings" / "direct_actuators.bind"}
{manager_extra}{vehicle_extra}""")
    return path


def _launch_errors(path, tmp_path):
    run = subprocess.run(
        LAUNCH + [str(path), "--out", str(tmp_path / "run")], capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 2 and "Traceback" not in run.stderr, run.stderr
    return run.stderr


def test_misspelt_param_newline_in_a_value_and_reserved_vehicle_ids(tmp_path):
    declared = (HERE / "mission.chasm").read_text()
    assert "param cycles" in declared
    err = _launch_errors(_scenario(tmp_path, manager_extra="        params: {cycels: 5}\n"), tmp_path)
    assert (
        f"{tmp_path / 's.yaml'}:10:18: vehicles[0].managers[0].params.cycels: the plan mission.chasm "
        "declares no parameter 'cycels'; did you mean 'cycles'?" in err
    )
    err = _launch_errors(_scenario(tmp_path, manager_extra='        params: {cycles: "5\\nstate evil"}\n'), tmp_path)
    assert "vehicles[0].managers[0].params.cycles: must not hold a newline" in err
    for vid in ("SIM", "MODEM"):
        err = _launch_errors(_scenario(tmp_path, vid=vid), tmp_path)
        assert f"{tmp_path / 's.yaml'}:4:9: vehicles[0].id: '{vid}' is reserved" in err
    err = _launch_errors(_scenario(tmp_path, vehicle_extra="    nav: {source: ekf, rate: 0}\n"), tmp_path)
    assert "vehicles[0].nav.rate: must be > 0" in err
    err = _launch_errors(_scenario(tmp_path, manager_extra="        status_rate: -2\n"), tmp_path)
    assert f"{tmp_path / 's.yaml'}:10:22: vehicles[0].managers[0].status_rate: must be in [0, 1000]" in err


def test_sim_config_refusals_name_file_line_col(tmp_path):
    from sim.config import load

    cases = {
        b"vehicle: {id: SIM}\n": "1:15: vehicle.id: 'SIM' is reserved",
        b'multihil: {client_id: "a\\nb"}\n': "1:23: multihil.client_id: must not hold a newline",
        b"sensors: {gps: {rate_hz: .nan}}\n": "1:26: sensors.gps.rate_hz: must be finite",
        b"simulation: {clock: warp}\n": "1:21: simulation.clock: expected one of: realtime, scaled, lockstep",
        b"sonar: {targets: {mines: 100000}}\n": "1:26: sonar.targets.mines: must be in [0, 1000]",
        b"modem: {max_frame_bytes: 0}\n": "1:26: modem.max_frame_bytes: must be in [1, 32767]",
        b"environment: {sound_speed_mps: -1}\n": "1:32: environment.sound_speed_mps: must be > 0",
    }
    for data, want in cases.items():
        p = tmp_path / "c.yaml"
        p.write_bytes(data)
        with pytest.raises(ConfigError) as exc:
            load(p)
        assert any(e.startswith(f"{p}:{want}") for e in exc.value.errors), (data, exc.value.errors)


def test_command_line_overrides_are_checked(tmp_path):
    run = subprocess.run(
        LAUNCH + [str(HERE / "two_vehicles.yaml"), "--warp", "nan", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.returncode == 2 and "--warp must be a number > 0" in run.stderr and "Traceback" not in run.stderr
    from tools.nav.survey_log import DEFAULT_CONFIG, apply_overrides

    text = DEFAULT_CONFIG.read_text()
    for item, want in (
        ("sensors.gps.noise=*a", "--set sensors.gps.noise:1:1: YAML alias '*a' refused"),
        ('vehicle.id="A\\u0007"', "must not hold control character U+0007"),
        ("a..b=1", "--set 'a..b=1': expected key.path=value"),
        (
            b"initial.north_m=2\xff".decode("utf-8", "surrogateescape"),
            "--set initial.north_m:1:2: not UTF-8 (byte 0xff)",
        ),
    ):
        with pytest.raises(ValueError) as exc:
            apply_overrides(text, [item])
        assert want in str(exc.value), (item, str(exc.value))

"""auvlcm.programs builds each program's command line in one place: every flag a
builder writes is one the program itself documents in its --help, and the LCM URL
is `--lcm-url` everywhere (the old spelling `--url` still understood)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import lcm
import pytest
from conftest import BUILD, ROOT, c_program

from auvlcm import programs


def _flags(cmd: list[str]) -> set[str]:
    return {a.split("=")[0] for a in cmd[1:] if a.startswith("-") and not re.fullmatch(r"-?[\d.]+", a)}


def _help(cmd: list[str]) -> str:
    p = subprocess.run([*cmd, "--help"], capture_output=True, text=True, timeout=60)
    return p.stdout + p.stderr


def _every_flag_documented(cmd: list[str], help_cmd: list[str]) -> None:
    text = _help(help_cmd)
    missing = sorted(f for f in _flags(cmd) if not re.search(re.escape(f) + r"\b", text))
    assert not missing, f"{help_cmd[-1]}: its --help does not know {missing}:\n{text}"


def test_manager_nav_recorder_and_simulator_builders_use_documented_flags(tmp_path):
    manager = programs.chasm_manager(
        BUILD,
        plan="p.chasm",
        bind="b.bind",
        vehicle="AUV1",
        name="PILOT",
        lcm_url="udpm://239.255.76.67:7667?ttl=0",
        rate_hz=20,
        status_rate_hz=2,
        plugin_path=[BUILD / "plugins"],
        params={"depth_kp": 0.5},
        key_file="team.key",
    )
    assert manager[0] == str(c_program("bin/chasm-manager"))
    assert manager[manager.index("--key-file") + 1] == "team.key"
    assert manager[manager.index("--lcm-url") + 1] == "udpm://239.255.76.67:7667?ttl=0"
    assert manager[manager.index("-D") + 1] == "depth_kp=0.5" and manager[manager.index("--rate") + 1] == "20"
    _every_flag_documented(manager, [manager[0]])
    nav = programs.auv_nav(BUILD, config="a.nav", vehicle="AUV1", lcm_url="udpm://x", rate_hz=20)
    _every_flag_documented(nav, [str(c_program("bin/auv-nav"))])
    front = programs.auv_front_estimate(
        BUILD, vehicle="AUV1", lcm_url="udpm://x", rate_hz=0.5, max_age_s=600, max_depth_m=20
    )
    assert front[front.index("--max-age") + 1] == "600"
    _every_flag_documented(front, [str(c_program("bin/auv-front-estimate"))])
    rec = programs.auv_recorder(BUILD, lcm_url="udpm://239.255.76.67:7667?ttl=0", log=tmp_path / "l", stats="s")
    assert "recv_buf_size=" in rec[rec.index("--lcm-url") + 1]
    _every_flag_documented(rec, [str(c_program("bin/auv-recorder"))])
    sim = programs.simulator("v.yaml", lcm_url="udpm://x", clock="scaled", warp=4, duration=60)
    assert sim[:3] == [sys.executable, "-m", "sim"] and sim[sim.index("--warp") + 1] == "4"
    _every_flag_documented(sim, sim[:3])
    logger = programs.lcm_logger(Path(lcm.LCM_BIN_DIR).resolve(), lcm_url="udpm://x", log="l")
    _every_flag_documented(logger, [logger[0]])


def test_driver_builders_use_documented_flags():
    gps = programs.device_driver(
        BUILD,
        "gps",
        vehicle="AUV1",
        lcm_url="udpm://x",
        port="/dev/ttyUSB0",
        baud=4800,
        raw=True,
        extra=programs.gps_origin_flags(45.0, -70.0),
    )
    assert gps[0] == str(c_program("bin/auv-gps")) and gps[gps.index("--baud") + 1] == "4800"
    _every_flag_documented(gps, [gps[0]])
    tcp = programs.device_driver(BUILD, "gps", vehicle="AUV1", lcm_url="udpm://x", tcp="10.0.0.2:4001")
    _every_flag_documented(tcp, [tcp[0]])
    with pytest.raises(ValueError):
        programs.device_driver(BUILD, "gps", vehicle="AUV1", lcm_url="udpm://x")
    replay = programs.driver_replay(BUILD, log="l", vehicle="AUV1", device="GPS", extra=["--min-year", "1990"])
    assert "--print" in replay
    _every_flag_documented(replay, [str(c_program("bin/auv-driver-replay"))])
    own = programs.dvl_flags(mounting_deg=(45.0, -2.5, 180.0), sigma_mps=0.02, ensemble_timeout_s=0.3)
    dvl = programs.device_driver(BUILD, "dvl", vehicle="AUV1", lcm_url="udpm://x", port="/dev/ttyUSB1", extra=own)
    assert dvl[dvl.index("--mounting") + 1] == "45.000000,-2.500000,180.000000"
    _every_flag_documented(dvl, [dvl[0]])
    replay = programs.driver_replay(BUILD, log="l", vehicle="AUV1", device="DVL", extra=own)
    _every_flag_documented(replay, [str(c_program("bin/auv-driver-replay"))])
    own = programs.modem_flags(
        {"AUV1": 1, "AUV2": 2}, rate=1, ack=True, cst=False, kind=2, answer_timeout_s=3, ack_timeout_s=9, rx_hold_s=1
    )
    modem = programs.device_driver(BUILD, "modem", vehicle="AUV1", lcm_url="udpm://x", tcp="10.0.0.3:4001", extra=own)
    assert modem[modem.index("--table") + 1] == "AUV1=1,AUV2=2" and modem[modem.index("--rate") + 1] == "1"
    _every_flag_documented(modem, [modem[0]])
    # the links of HIL at the wire: the time link's driver is the clock source (system clock)
    ts = programs.device_driver(BUILD, "timesync", vehicle="AUV1", lcm_url="udpm://x", tcp="10.0.0.1:4010")
    assert ts[ts.index("--clock") + 1] == "system"
    _every_flag_documented(ts, [ts[0]])
    own = programs.payload_flags(frame_timeout_s=0.2)
    payload = programs.device_driver(
        BUILD, "payload", vehicle="AUV1", lcm_url="udpm://x", port="/dev/ttyUSB2", clock="sim", extra=own
    )
    assert payload[payload.index("--frame-timeout") + 1] == "0.2"
    _every_flag_documented(payload, [payload[0]])
    fs = programs.frontseat(
        BUILD,
        vehicle="AUV1",
        lcm_url="udpm://x",
        port="/dev/ttyUSB3",
        origin=(41.5, -70.7),
        max_depth_m=40,
        min_speed_mps=0.5,
        max_speed_mps=2.0,
        helm_version=4,
        silent_after_s=2,
        clock="sim",
    )
    assert fs[0] == str(c_program("bin/auv-frontseat")) and fs[fs.index("--max-depth") + 1] == "40"
    _every_flag_documented(fs, [fs[0]])


@pytest.mark.parametrize(
    "program",
    [
        "chasm-manager",
        "auv-nav",
        "auv-front-estimate",
        "auv-recorder",
        "auv-gps",
        "auv-dvl",
        "auv-modem",
        "auv-timesync",
        "auv-payload",
        "auv-frontseat",
        "auv-driver-replay",
    ],
)
def test_c_programs_document_lcm_url(program):
    assert "--lcm-url" in _help([str(c_program(f"bin/{program}"))])


def test_python_commands_take_lcm_url_and_the_old_spelling():
    out = _help([sys.executable, "-m", "tools.console.auvctl"])
    assert "--lcm-url" in out and "--url " not in out
    p = subprocess.run(
        [sys.executable, "-m", "tools.console.auvctl", "--url", "udpm://239.255.76.67:7667?ttl=3", "pause", "AUV1"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    # the old spelling is taken (and named), and the URL it carried is checked like any other
    assert "--url is now spelled --lcm-url" in p.stderr and "ttl=3" in p.stderr and p.returncode != 0


def test_no_program_spells_the_url_flag_the_old_way():
    """The docs, tests and benches write --lcm-url; --url is only the old spelling
    the programs still parse."""
    files = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    offenders = []
    for f in files:
        if f.endswith((".py", ".md", ".yaml", ".sh")) and f not in (
            "tests/test_programs.py",
            "python/auvlcm/programs.py",
        ):
            text = (ROOT / f).read_text(errors="replace")
            offenders += [
                f"{f}:{n}" for n, line in enumerate(text.splitlines(), 1) if re.search(r"[\"' ]--url\b", line)
            ]
    assert not offenders, offenders


def test_radio_builders_use_documented_flags(tmp_path):
    sim = programs.radio_sim(
        vehicles=["AUV1", "AUV2"],
        lcm_url="udpm://x",
        settings={"bitrate_bps": 9600.0},
        pipes={"AUV1": tmp_path / "p"},
        lockstep_name="SHORE.radio",
        shore_lcm_url="udpm://y",
    )
    assert sim[sim.index("--pipe") + 1] == f"AUV1={tmp_path / 'p'}"
    assert sim[sim.index("--bitrate-bps") + 1] == "9600" and sim[sim.index("--vehicles") + 1] == "AUV1,AUV2"
    _every_flag_documented(sim, sim[:3])
    shore = programs.radio_shore(
        vehicles=["AUV1"], lcm_url="udpm://x", acoustic={"AUV1": 0}, link_timeout_s=1, retry_s=1
    )
    assert shore[shore.index("--acoustic") + 1] == "AUV1=0"
    _every_flag_documented(shore[2:], shore[:3])
    veh = programs.radio_vehicle(
        BUILD,
        vehicle="AUV1",
        spool=tmp_path,
        lcm_url="udpm://x",
        port=tmp_path / "pty",
        team_index=0,
        report_period_s=1,
        end_manager="PILOT",
        key_file=tmp_path / "k",
        peers=["AUV2", "AUV3"],
    )
    assert veh[0] == str(BUILD / "bin" / "auv-radio") and veh[veh.index("--spool") + 1] == str(tmp_path)
    _every_flag_documented(veh[1:], veh[:1])

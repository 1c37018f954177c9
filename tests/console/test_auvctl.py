"""auvctl over real LCM against a real chasm-manager (both builds): status,
pause and resume with their acks, a rejected plan and a rejected upload with
exit 1, nobody answering with exit 3, bad files with exit 2."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from manager_world import HERE, ManagerWorld

AUVCTL = [sys.executable, "-m", "tools.console.auvctl"]


def ctl(url: str, env: dict, *args: str, timeout: float = 5.0) -> subprocess.CompletedProcess:
    return subprocess.run(
        AUVCTL + ["--lcm-url", url, "--timeout", str(timeout), *args],
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_commands_and_status_against_a_real_manager(tmp_path, lcm_url, child_env, sanitized):
    allow = tmp_path / "allowlist"
    allow.write_text("0" * 64 + " other\n")
    (tmp_path / "plugins").mkdir()
    world = ManagerWorld(
        lcm_url, child_env, sanitized, extra=("--plugin-dir", str(tmp_path / "plugins"), "--allowlist", str(allow))
    )
    try:
        st = ctl(lcm_url, child_env, "status", "AUV1", timeout=20)
        assert st.returncode == 0, st.stdout + st.stderr
        assert "NAVIGATOR: running dive" in st.stdout and "plan dive.chasm" in st.stdout

        run = ctl(lcm_url, child_env, "pause", "AUV1", "--manager", "NAVIGATOR")
        assert (run.returncode, run.stdout) == (0, "AUV1 NAVIGATOR ok: paused\n"), run.stderr
        js = ctl(lcm_url, child_env, "status", "AUV1", "--json")
        assert js.returncode == 0 and json.loads(js.stdout)["managers"]["NAVIGATOR"]["run"] == "paused"
        run = ctl(lcm_url, child_env, "resume", "AUV1")  # every manager: the one heard answers
        assert (run.returncode, run.stdout) == (0, "AUV1 NAVIGATOR ok: resumed\n"), run.stderr

        bad = tmp_path / "bad.chasm"
        bad.write_text((HERE / "dive.chasm").read_text().replace("nav.depth_m >", "nav.depht_m >"))
        run = ctl(lcm_url, child_env, "load", "AUV1", str(bad), "--manager", "NAVIGATOR")
        assert run.returncode == 1 and run.stdout.startswith("AUV1 NAVIGATOR rejected: plan rejected"), run.stdout

        fake = tmp_path / "chasm_fake.so"
        fake.write_bytes(b"\x7fELF not a plugin")
        run = ctl(lcm_url, child_env, "upload", "AUV1", str(fake), "--manager", "NAVIGATOR")
        assert run.returncode == 1 and "rejected: plugin rejected: digest not in the allowlist" in run.stdout

        run = ctl(lcm_url, child_env, "abort", "AUV9", timeout=1.0)
        assert run.returncode == 3 and "no acknowledgement from AUV9" in run.stderr
        run = ctl(lcm_url, child_env, "status", "AUV9", timeout=1.0)
        assert run.returncode == 3 and "nothing heard from AUV9" in run.stderr
    finally:
        assert world.close() == 0


def test_usage_and_file_errors_exit_2(tmp_path, lcm_url, child_env):
    for args in (
        ["load", "AUV1", str(tmp_path / "missing.chasm")],
        ["upload", "AUV1", str(tmp_path / "none.so")],
        ["explode", "AUV1"],
        ["pause"],
    ):
        run = ctl(lcm_url, child_env, *args)
        assert run.returncode == 2 and "Traceback" not in run.stderr, (args, run.stderr)
    run = subprocess.run(
        AUVCTL + ["--lcm-url", "udpm://239.255.76.67:7667?ttl=3", "pause", "AUV1"],
        env=child_env,
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert run.returncode == 2 and "ttl=3" in run.stderr

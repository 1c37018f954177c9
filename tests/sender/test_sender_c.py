"""The C sender (c/sender/): its FIFO and its thread over real LCM, in both build
variants (the sanitized one under ASan/UBSan). Run inside tests/isolated_net.sh."""

from __future__ import annotations

import subprocess

import pytest
from conftest import c_program

VARIANTS = pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])


def run(*args, sanitized: bool, env: dict) -> subprocess.CompletedProcess:
    return subprocess.run(
        [c_program("bin/test_lcm_sender", sanitized), *args], capture_output=True, text=True, timeout=120, env=env
    )


@VARIANTS
def test_queue_keeps_order_blocks_when_full_flushes_and_drains_on_close(sanitized, child_env):
    r = run("queue", sanitized=sanitized, env=child_env)
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.count("ok queue") == 4, r.stdout


@VARIANTS
def test_sender_thread_delivers_everything_in_order_over_lcm(sanitized, child_env, lcm_url):
    r = run("lcm", lcm_url, sanitized=sanitized, env=child_env)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "ok lcm: 3020 messages" in r.stdout, r.stdout

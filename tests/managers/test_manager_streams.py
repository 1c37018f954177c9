"""Message variables over real LCM: a burst of messages published between two
cycles all reach the plan, in order, once; each posted message that decodes is
published in order after the cycle, a post that does not (garbage) or that is
too large is refused and counted, never a crash; undecodable and old inputs
never reach the stream. Both builds (the sanitizer build too)."""

from __future__ import annotations

import signal
import subprocess

import pytest
from conftest import ROOT, c_program, manager_cmd
from lcm_proc import pump, stop
from test_manager import World

from auv import modem_tx_t

HERE = ROOT / "tests" / "managers"
N = 150


def start_echo(url: str, env: dict, sanitized: bool) -> subprocess.Popen:
    plugins = c_program("plugins/chasm_test_msgs_lcm.so", sanitized).parent
    cmd = manager_cmd(HERE / "echo.chasm", HERE / "echo.bind", url, "--plugin-path", plugins, sanitized=sanitized)
    return subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, text=True)


def frame(utime: int, seq: int) -> bytes:
    m = modem_tx_t()
    m.utime, m.vehicle, m.seq, m.kind = utime, "AUV1", seq, modem_tx_t.KIND_TEAM
    m.payload = bytes([seq & 0xFF, (seq >> 8) & 0xFF, 7])
    m.n_bytes = len(m.payload)
    return m.encode()


@pytest.mark.parametrize("sanitized", [False, True], ids=["normal", "sanitized"])
def test_a_burst_of_messages_is_echoed_in_order_and_bad_posts_are_refused(lcm_url, child_env, sanitized):
    w = World(lcm_url)
    out: list = []
    w.rx.subscribe("TEST.OUT", modem_tx_t, lambda c, m: out.append(m), 1000)
    mgr = start_echo(lcm_url, child_env, sanitized)
    try:
        w.wait_for_first_cycle()
        # the burst: no clock tick in between, so all of it arrives between two cycles
        for seq in range(N):
            w.lc.publish("TEST.IN", frame(w.utime, seq))
        w.tick(0.1)
        assert pump(w.lc, lambda: len(out) >= N, timeout=30), f"{len(out)} of {N} echoed"
        assert [m.seq for m in out] == list(range(N))
        assert all(m.vehicle == "ECHO" and m.payload == bytes([s & 0xFF, s >> 8, 7]) for s, m in zip(range(N), out))
        s = w.status[-1]
        assert (s.messages_in, s.messages_out, s.messages_missed, s.posts_refused) == (N, N, 0, 0)
        # hostile: a post that is garbage (seq -1), one over 64 KiB (seq -2),
        # an input that does not decode, one older than the newest accepted
        w.lc.publish("TEST.IN", frame(w.utime, -1))
        w.lc.publish("TEST.IN", frame(w.utime, -2))
        w.lc.publish("TEST.IN", b"\x00garbage, not a modem_tx_t")
        w.lc.publish("TEST.IN", frame(w.utime - 50_000, 999))
        w.lc.publish("TEST.IN", frame(w.utime, N))
        w.tick(0.1)
        assert pump(w.lc, lambda: len(out) >= N + 1 and w.status[-1].posts_refused >= 2, timeout=30)
        assert out[-1].seq == N and len(out) == N + 1
        s = w.status[-1]
        assert (s.messages_in, s.messages_out, s.posts_refused) == (N + 3, N + 1, 2)
        assert s.decode_errors == 1 and s.dropped_out_of_order == 1
    finally:
        rc = stop(mgr, signal.SIGTERM)
    err = mgr.stderr.read()
    assert rc == 0, err
    assert f"messages: {N + 3} in, {N + 1} out, 0 missed, 2 posts refused" in err, err
    assert "refused a 26-byte message posted to 'tx'" in err, err

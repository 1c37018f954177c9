"""A host agent with --key-file over real LCM: auv-agentctl with the key is
obeyed (its resends answered, not refused as replays); without it, or with
a forged, replayed or wrong-key command, the agent refuses with the reason,
acts on nothing and counts the reason in its process table. A key file open
to others stops the agent at start."""

from __future__ import annotations

import hashlib

from agents import AgentProc, Tables, ctl, wait_until

from auv import agent_ack_t, agent_command_t
from auvlcm import auth
from tools.hosts.agent_launch import Keepalive
from tools.hosts.agentctl import Control

KEY = auth.Key("team-a", bytes(range(7, 39)))


def _command(seq: int, kind: int = agent_command_t.CMD_STOP) -> agent_command_t:
    c = agent_command_t()
    c.utime, c.host, c.sender, c.seq, c.command = 1, "alpha", "test", seq, kind
    return c


def test_only_signed_agent_commands_are_obeyed(tmp_path, lcm_url, child_env):
    keys = tmp_path / "team.key"
    keys.write_text(f"{KEY.id} {KEY.secret.hex()}\n")
    keys.chmod(0o600)
    agent = AgentProc("alpha", lcm_url, tmp_path / "agents", child_env, extra=("--key-file", str(keys)))
    tables = Tables(lcm_url, ["alpha"])
    try:
        wait_until(lambda: tables.latest("alpha"), 30, "the agent publishes a table")
        ok = ctl(lcm_url, child_env, "stop", "--host", "alpha", "--key-file", str(keys), "--timeout", "20")
        assert ok.returncode == 0 and "alpha: ok: nothing was running" in ok.stdout, ok.stdout + ok.stderr
        bare = ctl(lcm_url, {**child_env, "AUV_KEY_FILE": ""}, "stop", "--host", "alpha", "--timeout", "20")
        assert bare.returncode == 3 and "commands are not authenticated" in bare.stderr
        assert "alpha: refused: refused: unsigned command" in bare.stderr

        def answer(c: agent_command_t) -> agent_ack_t:
            tables.publish("AGENT.alpha.CMD", c)
            return wait_until(
                lambda: next((a for a in list(tables.acks) if a.seq == c.seq and a.sender == "test"), None),
                30,
                f"ack {c.seq}",
            )

        ring = auth.KeyRing((KEY,))
        signed = auth.sign(_command(10), ring, "test")
        assert answer(signed).result == agent_ack_t.RESULT_OK
        tables.acks.clear()
        assert answer(signed).message == "refused: replay (counter not above the newest from its sender)"
        forged = _command(11)
        forged.auth.key_id, forged.auth.sender, forged.auth.counter = KEY.id, "test", auth.next_counter()
        forged.auth.mac, forged.auth.mac_len = hashlib.sha256(b"x").digest(), 32
        assert answer(forged).message == "refused: bad MAC"
        other = auth.KeyRing((auth.Key("team-b", KEY.secret),))
        assert answer(auth.sign(_command(12), other, "test")).message == "refused: unknown key id"
        t = wait_until(lambda: (x := tables.latest("alpha")) and x.auth_bad_mac == 1 and x, 30, "counts in the table")
        assert (t.auth_unsigned, t.auth_unknown_key, t.auth_replay, t.auth_stale) == (1, 1, 1, 0)
        # auv-launch --agents' keepalives, signed on their own thread as the launcher sends them
        ctl_ = Control(lcm_url, ring)
        keep = Keepalive(lcm_url, ctl_, ["alpha"], "")
        keep.start()
        try:
            alive = lambda: [a for a in list(tables.acks) if a.sender == ctl_.sender and a.message == "alive"]  # noqa: E731
            wait_until(lambda: len(alive()) >= 2, 30, "two keepalives answered")
        finally:
            keep.done = True
            keep.join()
        assert not [a for a in list(tables.acks) if a.sender == ctl_.sender and a.message != "alive"]
    finally:
        tables.close()
        agent.stop()
    keys.chmod(0o640)
    loose = AgentProc("beta", lcm_url, tmp_path / "agents", child_env, extra=("--key-file", str(keys)))
    assert loose.p.wait(timeout=30) == 2
    assert "key file open to group or others (mode 0640): chmod 600 it" in loose.text()

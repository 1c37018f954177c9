"""Authentication end to end through the radio: a manager that takes only
signed commands (--key-file) acts on a pause the operator's tool signed,
carried in chunks by both gateways byte for byte, and refuses an unsigned one
carried the same way (docs/radio.md, "Authentication")."""

from __future__ import annotations

import signal

from lcm_proc import stop
from test_manager import start_manager
from test_manager_auth import RING, write_keys
from test_radio_e2e import Sea, _procs, _show

from auv import mission_command_t
from auv import radio_command_status_t as cs
from auvlcm import auth


def test_a_signed_command_crosses_the_radio_and_an_unsigned_one_is_refused(lcm_url, child_env, tmp_path):
    w = Sea(lcm_url)
    mgr = start_manager(lcm_url, child_env, extra=["--key-file", write_keys(tmp_path / "team.key")])
    procs = _procs(lcm_url, child_env, tmp_path / "spool")
    try:
        w.north = 100.0  # at the surface, in range
        w.wait_for_first_cycle()
        # once the shore hears it: with the radio down a pause would go acoustically, and
        # the acoustic route is not authenticated yet (docs/radio.md)
        assert w.sail(20.0, 0.0, lambda: bool(w.reports))
        for seq, signed in ((601, True), (602, False)):
            m = mission_command_t()
            m.utime, m.vehicle, m.seq, m.command, m.reason = w.utime, "AUV1", seq, mission_command_t.CMD_PAUSE, "t"
            if signed:
                auth.sign(m, RING, "radio-test")
            w.lc.publish("SHORE.AUV1.MISSION_CMD", m.encode())
        done = (cs.STATE_ACKNOWLEDGED,)
        assert w.sail(40.0, 0.0, lambda: all(w.last(s) and w.last(s).state in done for s in (601, 602))), [
            _show(w.last(s)) for s in (601, 602)
        ]
        assert "NAVIGATOR ok" in w.last(601).message, w.last(601).message
        assert "NAVIGATOR rejected" in w.last(602).message, w.last(602).message
    finally:
        codes = [stop(p, signal.SIGTERM) for p in procs]
        assert stop(mgr, signal.SIGTERM) == 0
    assert codes == [0, 0, 0]

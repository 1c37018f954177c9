"""The console's radio view (tools/console/radio_view.py): the link, the last
status home and each command's state per vehicle, from the shore's channels."""

from __future__ import annotations

import json
import re

from auv import mission_ack_t, radio_link_t, radio_report_t
from auv import radio_command_status_t as cs
from tools.console.model import CHANNELS, Model


def test_the_model_keeps_link_report_and_commands_per_vehicle():
    for ch in ("AUV1.RADIO_LINK", "SHORE.AUV1.RADIO_CMD_STATUS", "SHORE.AUV1.RADIO_REPORT", "SHORE.AUV1.MISSION_ACK"):
        assert re.fullmatch(CHANNELS, ch), ch
    m = Model()
    link = radio_link_t()
    link.utime, link.vehicle, link.up, link.antenna_clear, link.range_m = 10_000_000, "AUV1", True, True, 812.34
    assert m.apply("AUV1.RADIO_LINK", link)
    rep = radio_report_t()
    rep.utime, rep.vehicle, rep.mission, rep.contacts, rep.depth_m = 12_000_000, "AUV1", "RUNNING survey/line3", 4, 0.2
    assert m.apply("SHORE.AUV1.RADIO_REPORT", rep)
    for state, held in ((cs.STATE_QUEUED, 0), (cs.STATE_IN_FLIGHT, 2048), (cs.STATE_ACKNOWLEDGED, 4096)):
        s = cs()
        s.utime, s.vehicle, s.transfer_id, s.seq, s.what, s.state = 13_000_000, "AUV1", 77, 5, "upload survey 2", state
        s.route, s.bytes_total, s.bytes_held, s.message = (
            "radio",
            4096,
            held,
            "NAVIGATOR ok: loaded" if held == 4096 else "",
        )
        assert m.apply("SHORE.AUV1.RADIO_CMD_STATUS", s)
    ack = mission_ack_t()
    ack.utime, ack.vehicle, ack.manager, ack.seq, ack.message = 13_000_000, "AUV1", "NAVIGATOR", 5, "loaded"
    assert m.apply("SHORE.AUV1.MISSION_ACK", ack)
    v = json.loads(m.now_json())["vehicles"]["AUV1"]
    assert v["radio"]["link"]["up"] and v["radio"]["link"]["range_m"] == 812.3
    assert v["radio"]["report"]["mission"] == "RUNNING survey/line3" and v["radio"]["report"]["t"] == 12.0
    assert v["radio"]["commands"] == [
        {
            "id": "77",
            "seq": 5,
            "what": "upload survey 2",
            "state": "acknowledged",
            "route": "radio",
            "held": 4096,
            "total": 4096,
            "message": "NAVIGATOR ok: loaded",
            "t": 13.0,
        }
    ]
    assert v["acks"][-1]["manager"] == "NAVIGATOR" and "SHORE" not in json.loads(m.now_json())["vehicles"]

"""The console's radio view (tools/console/radio_view.py): the link, the last
status home and each command's state per vehicle, from the shore's channels;
in the model, and on the page in a real browser."""

from __future__ import annotations

import json
import re
import sys
import time

import lcm
from conftest import ROOT

from auv import mission_ack_t, radio_link_t, radio_report_t
from auv import radio_command_status_t as cs
from tools.console.model import CHANNELS, Model

sys.path.insert(0, str(ROOT / "tests" / "console"))
from browser import Browser  # noqa: E402
from console_fixtures import ARTIFACTS, Console, chromium  # noqa: E402, F401


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


def test_the_page_shows_the_radio(lcm_url, child_env, chromium):  # noqa: F811
    """In a real browser: the link, the last report with its age, a command's progress."""
    console = Console(["--lcm-url", lcm_url, "--shore"], child_env)
    browser = Browser(chromium)
    lc = lcm.LCM(lcm_url)
    try:
        browser.open(console.url)
        link = radio_link_t()
        link.utime, link.vehicle, link.up, link.antenna_clear, link.range_m = 20_000_000, "AUV1", True, True, 812.0
        rep = radio_report_t()
        rep.utime, rep.vehicle, rep.mission, rep.contacts = 15_000_000, "AUV1", "RUNNING survey/line3", 4
        s = cs()
        s.utime, s.vehicle, s.transfer_id, s.seq, s.what, s.state = 20_000_000, "AUV1", 77, 5, "upload survey 2", 1
        s.route, s.bytes_total, s.bytes_held = "radio", 4096, 2048
        text = "(document.querySelector('.vehicle[data-id=\"AUV1\"]') || {}).textContent || ''"
        deadline = time.monotonic() + 30
        while "in flight 50% of 4096 bytes" not in browser.eval(text):
            assert time.monotonic() < deadline, browser.eval(text)
            lc.publish("AUV1.RADIO_LINK", link.encode())
            lc.publish("SHORE.AUV1.RADIO_REPORT", rep.encode())
            lc.publish("SHORE.AUV1.RADIO_CMD_STATUS", s.encode())
            time.sleep(0.2)
        shown = browser.eval(text)
        assert "radio: up (antenna clear, 812.0 m)" in shown, shown
        assert "last report 5.0 s ago" in shown and "RUNNING survey/line3 · contacts 4" in shown, shown
        assert "upload survey 2 (radio): in flight 50% of 4096 bytes" in shown, shown
        browser.screenshot(ARTIFACTS / "radio.png")
    finally:
        browser.close()
        assert console.stop() == 0

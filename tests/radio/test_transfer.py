"""The radio's chunked transfers at the unit level, the shore's side
(tools/radio/outbox.py): a transfer cut by a dive and resumed from what the
vehicle holds, expiry, and the retries' back-off. The vehicle's side (the
reassembly and every kind of bad input) is auv-radio's, tested in C:
tests/drivers/test_radio.c."""

from __future__ import annotations

import os

import pytest

from auv import radio_ack_t
from auv import radio_command_status_t as cs
from tools.radio.outbox import Outbox

DATA = os.urandom(5000)


def test_the_outbox_resumes_after_a_dive_and_expires_what_never_goes():
    box = Outbox("AUV1", chunk_bytes=512, window=4, retry_s=2.0, link_timeout_s=3.0, expiry_s=100.0)
    t = box.submit("PLUGIN_UPLOAD", DATA, 42, "upload x", 0.0)
    assert box.due(0.0, 0) == []  # never heard: queued
    box.heard(1.0)
    sent = box.due(1.0, 0)
    assert [c.index for c in sent] == [0, 1, 2, 3] and t.state == cs.STATE_IN_FLIGHT
    ack = radio_ack_t()
    ack.transfer_id, ack.next_index, ack.state = t.tid, 2, radio_ack_t.STATE_HOLDING
    box.on_ack(ack, 1.5)
    assert [c.index for c in box.due(1.5, 0)] == [4, 5]
    assert box.due(10.0, 0) == []  # dived: not heard for 8.5 s
    box.heard(20.0, holding={t.tid: 3})  # its report at the next surfacing
    assert [c.index for c in box.due(20.0, 0)] == [3, 4, 5, 6]
    ack.state = radio_ack_t.STATE_DONE
    box.on_ack(ack, 21.0)
    assert t.state == cs.STATE_DELIVERED and box.queue == type(box.queue)()
    assert box.on_manager_ack(42, "NAVIGATOR ok").state == cs.STATE_ACKNOWLEDGED
    late = box.submit("MISSION_CMD", b"abc", 43, "pause", 22.0)
    box.due(200.0, 0)
    assert late.state == cs.STATE_EXPIRED and "nothing changed" in late.message
    states = [(s.transfer_id == t.tid, s.state) for s in box.statuses(0)]
    assert (True, cs.STATE_ACKNOWLEDGED) in states and (False, cs.STATE_EXPIRED) in states


def test_retries_back_off_and_start_again_at_the_next_surfacing():
    """Unanswered chunks are resent after retry_s, then 2, 4, 8, 16 x that: a slow
    air must not fill the radio's queue with copies; heard again after a dive,
    the shore starts over from what the vehicle holds at once."""
    box = Outbox("AUV1", chunk_bytes=512, window=2, retry_s=1.0, link_timeout_s=100.0)
    box.submit("PLUGIN_UPLOAD", DATA, 1, "upload", 0.0)
    box.heard(0.0)
    resent = [t for t in (x * 0.25 for x in range(1, 200)) if box.due(t, 0)]
    assert resent == pytest.approx([0.25, 1.5, 3.75, 8.0, 16.25, 32.5, 48.75])
    box.heard(200.0)  # the link timed out meanwhile: it surfaced
    assert [c.index for c in box.due(200.0, 0)] == [0, 1]

"""The radio's chunked transfers at the unit level (tools/radio): the shore's
outbox against the vehicle's assembler, a transfer cut and resumed, a restart
of the vehicle side, and every kind of bad input refused with a reason,
counted, with nothing handed on and the spool bounded."""

from __future__ import annotations

import hashlib
import os

import pytest

from auv import radio_ack_t, radio_chunk_t
from auv import radio_command_status_t as cs
from tools.radio import assembler as asm
from tools.radio.assembler import Assembler
from tools.radio.outbox import Outbox

DATA = os.urandom(5000)


def chunks(data: bytes, tid: int = 7, size: int = 512, channel: str = "PLUGIN_UPLOAD") -> list[radio_chunk_t]:
    box = Outbox("AUV1", chunk_bytes=size, window=10**6)
    t = box.submit(channel, data, 1, "test", 0.0)
    t.tid = tid
    box.heard(0.0)
    return box.due(0.0, 0)


def feed(a: Assembler, cs_: list[radio_chunk_t], now: float = 0.0):
    return [a.offer(c, now) for c in cs_]


def test_in_order_chunks_give_the_whole_once(tmp_path):
    a = Assembler("AUV1", tmp_path)
    offers = feed(a, chunks(DATA))
    assert [o.state for o in offers] == ["holding"] * 9 + ["done"]
    assert offers[-1].data == DATA and offers[-1].channel == "PLUGIN_UPLOAD"
    assert [o.next_index for o in offers] == list(range(1, 11))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["done.json"]  # nothing partial left
    again = a.offer(chunks(DATA)[-1], 1.0)  # the last chunk repeated: not handed on twice
    assert again.state == "done" and again.data is None and a.refused["duplicate"] == 1


def test_a_restart_resumes_from_the_spool(tmp_path):
    cs_ = chunks(DATA)
    a = Assembler("AUV1", tmp_path)
    feed(a, cs_[:4])
    with (tmp_path / "7.part").open("ab") as f:
        f.write(b"half a chunk written when the power went")
    b = Assembler("AUV1", tmp_path)  # the gateway restarted
    assert b.holding() == [(7, 4)]
    offers = feed(b, cs_[4:])
    assert offers[-1].state == "done" and offers[-1].data == DATA


@pytest.mark.parametrize(
    "mutate, key, reason",
    [
        (lambda c: setattr(c, "index", 5), "unknown transfer", "not held"),
        (lambda c: setattr(c, "channel", "CHASM.NAVIGATOR"), "channel", "is not carried"),
        (lambda c: setattr(c, "vehicle", "AUV2"), "wrong vehicle", "addressed to"),
        (lambda c: setattr(c, "sha256_hex", "XYZ"), "bad digest", "64 lowercase hex"),
        (lambda c: setattr(c, "total_bytes", asm.MAX_BYTES + 1), "too large", "at most"),
        (lambda c: setattr(c, "count", 10**9), "too many", "chunks for"),
        (lambda c: setattr(c, "count", 1), "too few", "cannot hold"),
        (lambda c: setattr(c, "index", -1), "too many", "chunk -1 of"),
    ],
)
def test_bad_first_chunks_are_refused_and_nothing_is_kept(tmp_path, mutate, key, reason):
    a = Assembler("AUV1", tmp_path)
    c = chunks(DATA)[0]
    mutate(c)
    o = a.offer(c, 0.0)
    assert o.data is None and reason in o.reason and a.refused[key] == 1, o
    assert a.holding() == [] and not list(tmp_path.glob("*.part"))


def test_out_of_order_duplicated_and_foreign_chunks_are_refused_and_counted(tmp_path):
    a = Assembler("AUV1", tmp_path)
    cs_ = chunks(DATA)
    feed(a, cs_[:3])
    o = a.offer(cs_[5], 0.0)
    assert o.state == "holding" and o.next_index == 3 and "out of order: expected 3" in o.reason
    o = a.offer(cs_[1], 0.0)
    assert o.next_index == 3 and "duplicate chunk 1" in o.reason
    other = chunks(os.urandom(5000))[3]  # same id, another transfer's header
    o = a.offer(other, 0.0)
    assert "does not match" in o.reason and o.next_index == 3
    over = chunks(DATA)[3]
    over.index = 10
    o = a.offer(over, 0.0)
    assert o.reason == "chunk 10 of 10" and a.holding() == [(7, 3)]  # the transfer is kept
    offers = feed(a, cs_[3:])
    assert offers[-1].data == DATA
    assert a.refused == {"out of order": 1, "duplicate": 1, "another transfer": 1, "too many": 1}


def test_a_wrong_digest_drops_the_whole(tmp_path):
    a = Assembler("AUV1", tmp_path)
    cs_ = chunks(DATA)
    for c in cs_:
        c.sha256_hex = hashlib.sha256(b"something else").hexdigest()
    offers = feed(a, cs_)
    assert offers[-1].state == "refused" and "does not match its SHA-256" in offers[-1].reason
    assert offers[-1].data is None and a.refused["wrong digest"] == 1
    assert not list(tmp_path.glob("*.part")) and a.holding() == []


def test_chunks_that_overrun_the_declared_size_are_refused(tmp_path):
    a = Assembler("AUV1", tmp_path)
    cs_ = chunks(DATA)
    big = chunks(DATA, size=4096)[0]  # same header values but 4096 bytes in one chunk
    big.count, big.total_bytes, big.sha256_hex = cs_[0].count, cs_[0].total_bytes, cs_[0].sha256_hex
    feed(a, cs_[:9])
    big.index = 9
    o = a.offer(big, 0.0)
    assert "goes past the declared 5000 bytes" in o.reason and a.holding() == [(7, 9)]


def test_memory_is_bounded_and_never_ending_transfers_expire(tmp_path):
    a = Assembler("AUV1", tmp_path, idle_expiry_s=60.0)
    for tid in range(1, asm.MAX_TRANSFERS + 1):
        a.offer(chunks(DATA, tid=tid)[0], 0.0)
    o = a.offer(chunks(DATA, tid=99)[0], 1.0)
    assert o.state == "refused" and "already in progress" in o.reason
    assert len(list(tmp_path.glob("*.part"))) == asm.MAX_TRANSFERS
    o = a.offer(chunks(DATA, tid=99)[0], 100.0)  # the others never ended: expired first
    assert o.state == "holding" and a.holding() == [(99, 1)]
    assert a.refused["never ended: expired"] == asm.MAX_TRANSFERS


def test_a_flood_of_garbage_keeps_nothing(tmp_path):
    a = Assembler("AUV1", tmp_path)
    c = chunks(b"x" * 3000)[0]
    for i in range(5000):
        c.transfer_id, c.index = 1000 + i, 1 + i % 3
        a.offer(c, float(i))
    assert a.refused["unknown transfer"] == 5000 and a.holding() == []
    assert not list(tmp_path.glob("*.part"))


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

"""auv-recorder reads the udpm group on sockets of its own
(c/common/lcm_udpm_reader.c, c/recorder/rec_input.c), not through liblcm:
what liblcm did for it must still hold. Fragmented messages from several
senders come out whole and in order, each event keeps its own receive time,
--channel still selects, and datagrams that are not LCM (or fragments that
never complete) are counted and dropped without losing anything after them.
Over real LCM, both build variants."""

from __future__ import annotations

import json
import random
import signal
import socket
import struct
import subprocess
import threading
import time

import lcm
import pytest
from lcm_proc import stop
from test_recorder import WARMUP, events, recorder_cmd, wait_logged


def start(variant_dir, url, log, stats, child_env, *extra, env=None):
    return subprocess.Popen(
        recorder_cmd(variant_dir, url, log, stats, "--no-lockstep", *extra),
        env={**child_env, **(env or {})},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def finish(rec) -> str:
    rc = stop(rec, signal.SIGINT)
    out, err = rec.communicate()
    assert rc == 0, out + err
    assert err == "", err  # no sanitizer report
    return out


def wait_recorded(log, rec, channel: str, timeout: float = 20.0) -> None:
    """Until the recorder's log holds a message on channel (it is read in
    arrival order: everything sent before it is in too), the recorder alive."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            if any(ch == channel for ch, _ in events(log)):
                return
        except (OSError, ValueError):
            pass  # a half-written event: read again
        assert rec.poll() is None, f"auv-recorder exited: {rec.communicate()}"
        assert time.monotonic() < deadline, f"{channel} never recorded"
        time.sleep(0.05)


def wait_log_holds(log, rec, nbytes: int, timeout: float = 60.0) -> None:
    """Until the recorder's log file holds nbytes (flow control for a sender:
    the recorder's socket buffer never has to hold more than a window), the
    recorder alive."""
    deadline = time.monotonic() + timeout
    while (log.stat().st_size if log.exists() else 0) < nbytes:
        assert rec.poll() is None, f"auv-recorder exited: {rec.communicate()}"
        assert time.monotonic() < deadline, f"the log never reached {nbytes} bytes"
        time.sleep(0.005)


def group_port(url: str) -> tuple[str, int]:
    host = url.split("//", 1)[1].split("?", 1)[0]
    g, p = host.split(":")
    return g, int(p)


@pytest.mark.parametrize("reader", ["own", "liblcm"])
def test_fragmented_messages_from_two_senders_come_out_whole(tmp_path, lcm_url, child_env, variant_dir, reader):
    """Two publishers at once, each mixing messages of one datagram with ones
    of up to 16 fragments: every message byte for byte, in each sender's order
    (on its own socket, and through liblcm with AUV_LCM_READER=0)."""
    url = lcm_url + "&recv_buf_size=8388608"
    log, stats = tmp_path / "rec.lcmlog", tmp_path / "stats.json"
    rec = start(variant_dir, url, log, stats, child_env, env={"AUV_LCM_READER": "0"} if reader == "liblcm" else {})
    rng = random.Random(7)
    sizes = [rng.choice([10, 1400, 70_000, 300_000, 1_000_000]) for _ in range(60)]
    plans = {
        name: [bytes([i % 251]) * 4 + rng.randbytes(n) for i, n in enumerate(sizes)] for name in ("BIG.A", "BIG.B")
    }
    try:
        wait_logged(log, WARMUP, lcm.LCM(url), rec, "auv-recorder")
        t0 = time.time()

        # flow control on what the recorder wrote, at most a megabyte ahead of
        # it: the test is reassembly, not the kernel's buffer
        sent, lock, window = [log.stat().st_size], threading.Lock(), 1 << 20

        def send(channel: str) -> None:
            lc = lcm.LCM(url)
            for body in plans[channel]:
                lc.publish(channel, body)
                with lock:
                    sent[0] += len(body)
                    behind = sent[0] - window
                wait_log_holds(log, rec, behind)

        threads = [threading.Thread(target=send, args=(ch,)) for ch in plans]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        lcm.LCM(url).publish("TEST.END", b"")
        wait_recorded(log, rec, "TEST.END")
        t1 = time.time()
    finally:
        out = finish(rec)
    log_events = list(lcm.EventLog(str(log), "r"))
    for channel, bodies in plans.items():
        got = [ev.data for ev in log_events if ev.channel == channel]
        assert len(got) == len(bodies), (channel, len(got), out)
        assert got == bodies, f"{channel}: a message came out different"
    stamps = [ev.timestamp for ev in log_events if ev.channel in plans]
    assert all(t0 * 1e6 - 1e6 <= s <= t1 * 1e6 + 1e6 for s in stamps), "receive stamps are not receive times"
    counts = json.loads(stats.read_text())
    assert counts["malformed"] == 0 and counts["incomplete"] == 0 and counts["missed"] == 0, counts


def test_datagrams_that_are_not_lcm_are_counted_and_dropped(tmp_path, lcm_url, child_env, variant_dir):
    """Garbage, cut-short headers, a channel without its end (or empty, or not
    UTF-8), a fragment that
    points past its message, and a fragmented message whose sender moved on
    before it completed: none is recorded, each is counted, and the message
    sent after them all is recorded."""
    log, stats = tmp_path / "rec.lcmlog", tmp_path / "stats.json"
    rec = start(variant_dir, lcm_url, log, stats, child_env)
    group, port = group_port(lcm_url)
    raw = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    raw.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)  # this machine only
    lc2 = struct.pack(">II", 0x4C433032, 1)
    lc3 = lambda seq, size, off, no, n: struct.pack(">IIIIHH", 0x4C433033, seq, size, off, no, n)  # noqa: E731
    malformed = [
        b"garbage that is not LCM",
        b"LC0",
        lc2,  # no channel at all
        lc2 + b"X" * 80,  # a channel longer than LCM allows, never ended
        lc2 + b"\0payload",  # an empty channel
        lc2 + b"AUV\xff\xfe\0payload",  # a channel that is not UTF-8 (no log reader could read it)
        lc2 + b"AUV\xc0\xae\0payload",  # an overlong UTF-8 form
        lc3(5, 100, 0, 0, 2)[:12],  # a fragment header cut short
        lc3(6, 100, 0, 0, 0) + b"CH\0" + b"x" * 10,  # zero fragments
        lc3(7, 100, 0, 3, 2) + b"x" * 10,  # fragment 3 of 2
        lc3(8, 100, 95, 1, 2) + b"x" * 10,  # past the message's end
    ]
    try:
        lc = lcm.LCM(lcm_url)
        wait_logged(log, WARMUP, lc, rec, "auv-recorder")
        for d in malformed:
            raw.sendto(d, (group, port))
        # the first of two fragments, then the same sender's next message: the first can never complete
        raw.sendto(lc3(9, 20, 0, 0, 2) + b"HALF\0" + b"a" * 10, (group, port))
        raw.sendto(lc3(10, 6, 0, 0, 1) + b"WHOLE\0" + b"123456", (group, port))
        lc.publish("AFTER", b"still recorded")
        wait_recorded(log, rec, "AFTER")
    finally:
        out = finish(rec)
        raw.close()
    recorded = events(log)
    assert ("AFTER", b"still recorded") in recorded
    assert ("WHOLE", b"123456") in recorded  # a one-fragment LC03 message is a message
    assert {ch for ch, _ in recorded} <= {WARMUP, "AFTER", "WHOLE"}, recorded
    counts = json.loads(stats.read_text())
    assert counts["malformed"] == len(malformed), counts
    assert counts["incomplete"] == 1, counts
    assert f"{len(malformed)} malformed datagrams, 1 fragmented messages never completed" in out, out


def test_channel_selects_what_is_recorded(tmp_path, lcm_url, child_env, variant_dir):
    log, stats = tmp_path / "rec.lcmlog", tmp_path / "stats.json"
    rec = start(variant_dir, lcm_url, log, stats, child_env, "--channel", r"AUV[12]\.TRUTH|TEST\..*")
    lc = lcm.LCM(lcm_url)
    try:
        wait_logged(log, WARMUP, lc, rec, "auv-recorder")
        for ch in ("AUV1.TRUTH", "AUV3.TRUTH", "AUV2.TRUTH", "AUV1.TRUTHX", "XAUV1.TRUTH", "TEST.END"):
            lc.publish(ch, ch.encode())
        wait_recorded(log, rec, "TEST.END")
    finally:
        finish(rec)
    got = [ch for ch, _ in events(log) if ch != WARMUP]
    assert got == ["AUV1.TRUTH", "AUV2.TRUTH", "TEST.END"]  # anchored, as lcm_subscribe anchors


def test_random_datagrams_never_crash_it_nor_reach_the_log(tmp_path, lcm_url, child_env, variant_dir):
    """2000 random datagrams, half of them with an LC02 or LC03 magic and
    random header fields (offsets, counts, sizes up to LCM's limit), from two
    senders: the recorder (both builds: ASan and UBSan watch it) keeps running,
    records none of them as a message it cannot be, and records what comes after."""
    log, stats = tmp_path / "rec.lcmlog", tmp_path / "stats.json"
    rec = start(variant_dir, lcm_url, log, stats, child_env)
    group, port = group_port(lcm_url)
    rng = random.Random(99)
    senders = [socket.socket(socket.AF_INET, socket.SOCK_DGRAM) for _ in range(2)]
    for s in senders:
        s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)  # this machine only
    try:
        lc = lcm.LCM(lcm_url)
        wait_logged(log, WARMUP, lc, rec, "auv-recorder")
        for i in range(2000):
            kind = rng.random()
            if kind < 0.25:
                head = struct.pack(">II", 0x4C433032, rng.getrandbits(32))
            elif kind < 0.5:
                n = rng.choice([1, 2, 3, rng.getrandbits(16)])
                head = struct.pack(
                    ">IIIIHH",
                    0x4C433033,
                    rng.getrandbits(3),  # few sequence numbers: fragments of "one" message collide
                    rng.choice([0, 10, 1000, 70_000, 1 << 28, rng.getrandbits(32)]),
                    rng.choice([0, 5, 995, rng.getrandbits(32)]),
                    rng.randrange(n + 1),
                    n,
                )
            else:
                head = b""
            body = rng.randbytes(rng.randrange(0, 1400))
            if rng.random() < 0.3:
                body = b"JUNK\0" + body  # a plausible channel
            senders[i % 2].sendto(head + body, (group, port))
            if i % 200 == 199:  # the test is the parser, not the socket buffer: let it catch up
                lc.publish(f"PACE.{i}", b"")
                wait_recorded(log, rec, f"PACE.{i}")
        lc.publish("AFTER", b"still recorded")
        wait_recorded(log, rec, "AFTER")
    finally:
        out = finish(rec)
        for s in senders:
            s.close()
    recorded = events(log)
    assert ("AFTER", b"still recorded") in recorded
    counts = json.loads(stats.read_text())
    assert counts["missed"] == 0, counts
    # every datagram was judged: a message (a random LC02 with a UTF-8 channel), or counted
    assert counts["malformed"] >= 1000, counts
    assert counts["received"] == len(recorded), counts
    assert "malformed datagrams" in out, out

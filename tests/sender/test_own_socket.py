"""FilteredLcm receiving on a socket of its own (auvlcm/own_socket.py over
c/common/lcm_udpm_reader.c): what lcm.LCM did must still hold - fileno()
readable exactly when a message waits, one message per handle(), handlers in
subscription order, fragmented messages whole - and the kernel filter follows
the subscriptions both ways. Over real LCM."""

from __future__ import annotations

import os
import select
import time

import lcm

from auvlcm.chanfilter import FilteredLcm


def readable(lc, timeout: float = 0.0) -> bool:
    return bool(select.select([lc.fileno()], [], [], timeout)[0])


def bound_sockets(port: int) -> int:
    """UDP sockets of this process bound to port."""
    inodes = set()
    with open("/proc/self/net/udp") as f:
        next(f)
        for line in f:
            cols = line.split()
            if int(cols[1].split(":")[1], 16) == port:
                inodes.add(cols[9])
    mine = set()
    for fd in os.listdir("/proc/self/fd"):
        try:
            target = os.readlink(f"/proc/self/fd/{fd}")
        except OSError:
            continue
        if target.startswith("socket:["):
            mine.add(target[8:-1])
    return len(inodes & mine)


def test_it_reads_its_own_socket_and_liblcm_receives_nothing(own_lcm, lcm_url):
    got: list[tuple[str, bytes]] = []
    own_lcm.subscribe("A", lambda c, d: got.append((c, d)))
    assert own_lcm.fileno() == own_lcm._own.fd
    lcm.LCM(lcm_url).publish("A", b"1")
    assert own_lcm.handle_timeout(2000) == 1
    assert got == [("A", b"1")]
    assert own_lcm.filtering
    # one socket of this process on the port: its own; liblcm made none (no receive thread)
    assert bound_sockets(int(lcm_url.split(":")[2].split("?")[0])) == 1


def test_fileno_is_readable_exactly_while_a_message_waits(own_lcm, lcm_url):
    got: list[bytes] = []
    own_lcm.subscribe("A", lambda c, d: got.append(d))
    tx = lcm.LCM(lcm_url)
    for i in range(3):
        tx.publish("A", bytes([i]))
    assert readable(own_lcm, 2.0)
    for i in range(3):
        assert readable(own_lcm, 2.0), f"message {i} waits but the descriptor says nothing"
        own_lcm.handle()  # one message per call, as lcm.LCM
        assert got == [bytes([k]) for k in range(i + 1)]
    assert not readable(own_lcm, 0.1)


def test_handlers_run_in_subscription_order_and_may_unsubscribe(own_lcm, lcm_url):
    order: list[str] = []
    subs = {}

    def once(c, d):
        order.append("once")
        own_lcm.unsubscribe(subs["once"])  # during the dispatch of this very message

    subs["first"] = own_lcm.subscribe("A.*", lambda c, d: order.append("first"))
    subs["once"] = own_lcm.subscribe("A", once)
    subs["last"] = own_lcm.subscribe("A", lambda c, d: order.append("last"))
    tx = lcm.LCM(lcm_url)
    tx.publish("A", b"")
    tx.publish("A", b"")
    assert own_lcm.handle_timeout(2000) == 1 and own_lcm.handle_timeout(2000) == 1
    assert order == ["first", "once", "last", "first", "last"]


def test_the_filter_narrows_again_on_unsubscribe(own_lcm, lcm_url):
    """After unsubscribing A the kernel drops A: the first message handled
    is the B sent after three As (liblcm's filter never narrowed)."""
    got: list[str] = []
    a = own_lcm.subscribe("A", lambda c, d: got.append(c))
    own_lcm.subscribe("B", lambda c, d: got.append(c))
    own_lcm.unsubscribe(a)
    tx = lcm.LCM(lcm_url)
    for _ in range(3):
        tx.publish("A", b"")
    tx.publish("B", b"")
    assert own_lcm.handle_timeout(2000) == 1
    assert got == ["B"]
    assert not readable(own_lcm, 0.1)


def test_a_fragmented_message_comes_out_whole(lcm_url):
    url = lcm_url + "&recv_buf_size=4194304"  # the url sizes the socket's buffer, as with liblcm
    rx = FilteredLcm(url)
    got: list[bytes] = []
    rx.subscribe("BIG", lambda c, d: got.append(d))
    body = os.urandom(500_000)  # about 8 fragments
    lcm.LCM(url).publish("BIG", body)
    deadline = time.monotonic() + 5
    while not got and time.monotonic() < deadline:
        rx.handle_timeout(100)
    assert got == [body]


def test_handle_all_takes_everything_queued(own_lcm, lcm_url):
    got: list[bytes] = []
    own_lcm.subscribe("A", lambda c, d: got.append(d))
    tx = lcm.LCM(lcm_url)
    for i in range(200):
        tx.publish("A", i.to_bytes(2, "big"))
    handled, deadline = 0, time.monotonic() + 10
    while handled < 200 and time.monotonic() < deadline:  # all may not be queued at once
        handled += own_lcm.handle_all(1000)
    assert handled == 200
    assert got == [i.to_bytes(2, "big") for i in range(200)]
    assert not readable(own_lcm, 0.1)  # nothing left behind in a half-read batch
    tx.publish("A", b"\xff\xff")
    assert own_lcm.handle_timeout(2000) == 1 and got[-1] == b"\xff\xff"  # one at a time again

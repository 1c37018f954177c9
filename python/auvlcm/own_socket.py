"""Receiving an LCM udpm group on a socket of one's own, from Python.

Through the lcm package every datagram wakes liblcm's receive thread, which
then wakes the caller through a pipe: two context switches per message, for
a simulator or a launcher that handles thousands of them per second. Here
the process reads the group's socket itself (c/common/lcm_udpm_reader.c, in
libauvlcm_sender.so), one datagram per call, so fileno() is readable exactly
when a message waits and select()/poll() loops work as with lcm.LCM. A kernel
channel filter built from the subscriptions (auvlcm/chanfilter.py) drops
what the process did not subscribe to, and narrows again on unsubscribe.
Publishing stays with an lcm.LCM that never subscribes (so it never starts
its receive thread). Handlers are called one message per handle(), in
subscription order, as lcm.LCM calls them; a pattern means what
lcm.LCM.subscribe's anchored regex means (re.fullmatch).

AUV_LCM_READER=0 leaves receiving to liblcm.
"""

from __future__ import annotations

import ctypes
import os
import re
import select
import sys
from typing import Callable

Handler = Callable[[str, bytes], None]


class _Msg(ctypes.Structure):
    _fields_ = [
        ("channel", ctypes.c_char_p),
        ("data", ctypes.c_void_p),
        ("len", ctypes.c_int),
        ("recv_utime", ctypes.c_int64),
    ]


class Rule(ctypes.Structure):
    """auv_chanfilter_rule_t (c/common/lcm_chanfilter.h)."""

    _fields_ = [
        ("channel", ctypes.c_char_p),
        ("payload", ctypes.c_char_p),
        ("payload_at", ctypes.c_int),
        ("payload_len", ctypes.c_int),
    ]


def bind(lib: ctypes.CDLL) -> None:
    """Declares the reader's functions on the loaded library."""
    p = ctypes.c_void_p
    lib.lcm_udpm_reader_open.argtypes = [ctypes.c_char_p, ctypes.c_long, ctypes.c_char_p, ctypes.c_size_t]
    lib.lcm_udpm_reader_open.restype = p
    lib.lcm_udpm_reader_close.argtypes = [p]
    lib.lcm_udpm_reader_close.restype = None
    lib.lcm_udpm_reader_fd.argtypes = [p]
    lib.lcm_udpm_reader_fd.restype = ctypes.c_int
    lib.lcm_udpm_reader_set_batch.argtypes = [p, ctypes.c_int]
    lib.lcm_udpm_reader_set_batch.restype = None
    lib.lcm_udpm_reader_next.argtypes = [p, ctypes.POINTER(_Msg)]
    lib.lcm_udpm_reader_next.restype = ctypes.c_int
    lib.auv_chanfilter_attach_fd.argtypes = [ctypes.c_int, ctypes.POINTER(Rule), ctypes.c_int]
    lib.auv_chanfilter_attach_fd.restype = ctypes.c_int


class Subscription:
    """What subscribe() returns: unsubscribe() takes it back."""

    def __init__(self, channel: str, handler: Handler) -> None:
        self.channel = channel
        self.match = re.compile(channel).fullmatch
        self.handler = handler

    def set_queue_capacity(self, _n: int) -> int:
        """Nothing queues in the process: the kernel's receive buffer (the
        url's recv_buf_size) is the queue."""
        return 0


class OwnReceiver:
    """The receiving half of an LCM instance on url; raises OSError when the
    socket cannot be opened (then let liblcm receive)."""

    def __init__(self, lib: ctypes.CDLL, url: str, filtering: bool) -> None:
        err = ctypes.create_string_buffer(160)
        r = lib.lcm_udpm_reader_open(url.encode(), 0, err, len(err))
        if not r:
            raise OSError(err.value.decode(errors="replace"))
        self._lib, self._r = lib, r
        lib.lcm_udpm_reader_set_batch(r, 1)
        self._next = lib.lcm_udpm_reader_next
        self._wait: Callable | None = None
        self._msg = _Msg()
        self._msg_ref = ctypes.byref(self._msg)
        self.fd = lib.lcm_udpm_reader_fd(r)
        self.subs: list[Subscription] = []
        self._routes: dict[str, list[Subscription]] = {}
        self.filtering = filtering
        self._told = False
        self._refilter()

    def _refilter(self) -> None:
        if not self.filtering:
            return
        rules = (Rule * max(1, len(self.subs)))()
        keep = []  # the encoded patterns must outlive the call
        for i, s in enumerate(self.subs):
            keep.append(s.channel.encode())
            rules[i].channel = keep[-1]
        if self._lib.auv_chanfilter_attach_fd(self.fd, rules, len(self.subs)) < 0 and not self._told:
            self._told = True
            err = os.strerror(ctypes.get_errno())
            print(f"lcm: the kernel refused the channel filter ({err}): receiving every channel", file=sys.stderr)

    def subscribe(self, channel: str, handler: Handler) -> Subscription:
        sub = Subscription(channel, handler)
        self.subs.append(sub)
        self._routes.clear()
        self._refilter()
        return sub

    def unsubscribe(self, sub: Subscription) -> None:
        self.subs.remove(sub)
        self._routes.clear()
        self._refilter()

    def _handle_one(self) -> bool:
        """Hands the next queued message to its subscriptions; False when
        nothing complete is queued."""
        rc = self._next(self._r, self._msg_ref)
        if rc == 1:
            self._dispatch()
            return True
        if rc < 0:
            raise OSError(ctypes.get_errno(), "LCM receive failed")
        return rc == 2  # a board took the report its clock waited for (read_with)

    def _dispatch(self) -> None:
        m = self._msg
        channel = m.channel.decode(errors="replace")
        data = ctypes.string_at(m.data, m.len)
        routes = self._routes.get(channel)
        if routes is None:
            routes = self._routes[channel] = [s for s in self.subs if s.match(channel)]
        for s in tuple(routes):  # a handler may subscribe or unsubscribe
            if s in self.subs:
                s.handler(channel, data)

    def read_with(self, next_fn: Callable, wait_fn: Callable, keep: object) -> None:
        """Read through next_fn(reader, msg) instead of lcm_udpm_reader_next,
        and wait through wait_fn(reader, msg, timeout_ms) instead of select:
        functions that take some messages themselves and return 2 when one of
        those is what the caller waits for (auvlcm/lockstep_board.py). keep:
        what they need alive as long as this receiver."""
        self._next = next_fn
        self._wait = wait_fn
        self._keep = keep

    def handle_timeout(self, timeout_ms: int) -> int:
        """1 when a message was handled, 0 when none came within timeout_ms."""
        if self._wait is not None:
            rc = self._wait(self._r, self._msg_ref, max(0, timeout_ms))
            if rc < 0:
                raise OSError(ctypes.get_errno(), "LCM receive failed")
            if rc == 1:
                self._dispatch()
            return 1 if rc else 0
        if self._handle_one():
            return 1
        ready, _, _ = select.select([self.fd], [], [], max(0, timeout_ms) / 1000.0)
        return 1 if ready and self._handle_one() else 0

    def handle_all(self, timeout_ms: int) -> int:
        """Waits up to timeout_ms for a message, then handles every message
        queued, reading them in batches (for a caller that acts only after
        all of them, not between two). Returns how many it handled."""
        if self.handle_timeout(timeout_ms) == 0:
            return 0
        n = 1
        self._lib.lcm_udpm_reader_set_batch(self._r, 64)
        try:
            while self._handle_one():
                n += 1
        finally:  # everything read was taken: one at a time again
            self._lib.lcm_udpm_reader_set_batch(self._r, 1)
        return n

    def handle(self) -> None:
        """Blocks until one message has been handled."""
        while not self._handle_one():
            select.select([self.fd], [], [])

    def close(self) -> None:
        if self._r:
            self._lib.lcm_udpm_reader_close(self._r)
            self._r = None

    def __del__(self) -> None:
        if getattr(self, "_r", None):
            self.close()

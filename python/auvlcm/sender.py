"""An lcm.LCM whose publish() hands messages to a C sender thread.

Why: a process that subscribes on a udpm URL also receives its own multicast
packets, so each lcm.LCM.publish() wakes liblcm's receive thread, and on a
virtual machine that wake-up costs the publishing thread 10-50 us: as much as
a physics step of the simulator. ThreadedLcm.publish() only copies the
message into a FIFO (c/sender/, built as build/lib/libauvlcm_sender.so and
loaded with ctypes); a sender thread with its own publish-only lcm_t sends
the messages in order. Nothing is dropped: a full queue makes publish() wait
(counted in stats()). flush() returns once everything published so far has
been handed to the kernel: call it before the process waits for others who
react to its messages.

Everything else (subscribe, handle, fileno, ...) is the wrapped lcm.LCM.
"""

from __future__ import annotations

import ctypes
import errno
import os
from pathlib import Path

import lcm

from auvlcm.chanfilter import FilteredLcm
from auvlcm.paths import build_dir

LIBRARY = "libauvlcm_sender.so"
DEFAULT_SPIN_US = 200
STAT_FIELDS = ("published", "sent", "send_errors", "full_waits", "sender_sleeps", "flushes")


class _Stats(ctypes.Structure):
    _fields_ = [(name, ctypes.c_uint64) for name in STAT_FIELDS]


class SenderUnavailable(RuntimeError):
    """The sender library is not built, or the sender could not start."""


def library_path() -> Path:
    return build_dir() / "lib" / LIBRARY


_libs: tuple[ctypes.PyDLL, ctypes.CDLL] | None = None


def _load() -> tuple[ctypes.PyDLL, ctypes.CDLL]:
    """The library twice: publish() through PyDLL (keeps the GIL: a copy into
    the queue is far cheaper than releasing and taking it back), the calls
    that may wait through CDLL (they release the GIL while they wait)."""
    global _libs
    if _libs is None:
        path = library_path()
        if not path.exists():
            raise SenderUnavailable(f"{path} is not built (make build)")
        fast, slow = ctypes.PyDLL(str(path)), ctypes.CDLL(str(path))
        p, u32, u64 = ctypes.c_void_p, ctypes.c_uint32, ctypes.c_uint64
        fast.auv_lcm_sender_publish.argtypes = [p, ctypes.c_char_p, ctypes.c_char_p, u32]
        fast.auv_lcm_sender_publish.restype = ctypes.c_int
        fast.auv_lcm_sender_pending.argtypes = [p]
        fast.auv_lcm_sender_pending.restype = u64
        slow.auv_lcm_sender_create.argtypes = [ctypes.c_char_p, u32, u32]
        slow.auv_lcm_sender_create.restype = p
        for name in ("auv_lcm_sender_flush", "auv_lcm_sender_destroy"):
            getattr(slow, name).argtypes = [p]
            getattr(slow, name).restype = None
        slow.auv_lcm_sender_get_stats.argtypes = [p, ctypes.POINTER(_Stats)]
        slow.auv_lcm_sender_get_stats.restype = None
        slow.auv_lcm_sender_last_error.argtypes = [p]
        slow.auv_lcm_sender_last_error.restype = ctypes.c_int
        _libs = (fast, slow)
    return _libs


class ThreadedLcm:
    """lcm.LCM(url) for receiving, a sender thread for publishing.

    slots: messages in flight before publish() waits; spin_us: how long the
    sender thread (and a waiting publisher) spins before sleeping. Waiting
    for the next message, the sender spins, then dozes in short sleeps (up
    to 20 ms), and only then sleeps until a publish() wakes it: while the
    loop runs fast its publish() stays a copy (measured: 3 us per message;
    10 to hundreds when it must wake the sender; 12-22 without the thread).
    After a flush() the sender sleeps at once, so a loop paced by a clock
    spends nothing on spinning. Default: 200 us, 0 when the process may run
    on one CPU only (a spinning sender would hold the publisher's only core).
    """

    def __init__(
        self, url: str, lc: lcm.LCM | FilteredLcm | None = None, slots: int = 512, spin_us: int | None = None
    ) -> None:
        if spin_us is None:
            spin_us = DEFAULT_SPIN_US if len(os.sched_getaffinity(0)) > 1 else 0
        fast, slow = _load()
        # an instance made here gets a channel filter (auvlcm/chanfilter.py)
        self.lc = lc = lc if lc is not None else FilteredLcm(url)
        handle = slow.auv_lcm_sender_create(url.encode(), slots, spin_us)
        if not handle:
            raise SenderUnavailable(f"cannot start an LCM sender on {url!r}")
        self._h = handle
        self._slow = slow
        self._publish = fast.auv_lcm_sender_publish
        self._pending = fast.auv_lcm_sender_pending
        self._channels: dict[str, bytes] = {}
        self._errors_reported = 0
        # the receiving side, bound once: the simulator polls fileno() every step
        self.fileno, self.handle, self.handle_timeout = lc.fileno, lc.handle, lc.handle_timeout
        self.subscribe, self.unsubscribe = lc.subscribe, lc.unsubscribe

    # -------------------------------------------------------------- publish
    def publish(self, channel: str, data: bytes) -> None:
        ch = self._channels.get(channel)
        if ch is None:
            ch = self._channels[channel] = channel.encode()
            if b"\0" in ch:
                raise ValueError(f"channel {channel!r} contains a NUL")
        if self._h is None:
            raise OSError(errno.EBADF, "publish on a closed ThreadedLcm")
        if type(data) is not bytes:
            data = bytes(data)
        if self._publish(self._h, ch, data, len(data)) != 0:
            raise MemoryError(f"cannot queue a message of {len(data)} bytes on {channel}")

    def flush(self) -> None:
        """Wait until every message published so far has been sent."""
        if self._h is not None:
            self._slow.auv_lcm_sender_flush(self._h)

    def pending(self) -> int:
        """Messages published and not yet sent."""
        return self._pending(self._h) if self._h is not None else 0

    def stats(self) -> dict[str, int]:
        if self._h is None:
            return dict(self._final)
        st = _Stats()
        self._slow.auv_lcm_sender_get_stats(self._h, ctypes.byref(st))
        return {name: getattr(st, name) for name in STAT_FIELDS}

    def last_error(self) -> str:
        """The last send failure ('' if none): sends happen on the sender thread."""
        code = self._slow.auv_lcm_sender_last_error(self._h) if self._h is not None else self._err
        return os.strerror(code) if code else ""

    def new_errors(self) -> str:
        """A line about send failures since the last call ('' if none): the loop
        prints it, since the failures happen on the sender thread."""
        errors = self.stats()["send_errors"]
        if errors == self._errors_reported:
            return ""
        self._errors_reported = errors
        return f"LCM send failed ({self.last_error()}): {errors} messages lost so far"

    def summary(self) -> str:
        st = self.stats()
        err = self.last_error()
        return (
            f"sender thread: {st['full_waits']} waits on a full queue, "
            f"{st['send_errors']} send errors{f' (last: {err})' if err else ''}"
        )

    def close(self) -> None:
        """Send what is queued, stop the thread. Receiving still works."""
        if self._h is not None:
            self.flush()
            self._final = self.stats()
            self._err = self._slow.auv_lcm_sender_last_error(self._h)
            self._slow.auv_lcm_sender_destroy(self._h)
            self._h = None

    def __del__(self) -> None:
        if getattr(self, "_h", None) is not None:
            self.close()

    # ------------------------------------------------------- everything else
    def __getattr__(self, name: str):
        if name in ("lc", "_h"):  # not set yet: __init__ failed part-way
            raise AttributeError(name)
        return getattr(self.lc, name)


def open_lcm(url: str, threaded: bool = True, log=print) -> FilteredLcm | ThreadedLcm:
    """An lcm.LCM(url) with a channel filter (auvlcm/chanfilter.py) that
    publishes from a sender thread, unless threaded is false or the library is
    not built (then it says so, and the caller publishes itself)."""
    if not threaded:
        return FilteredLcm(url)
    try:
        return ThreadedLcm(url)
    except SenderUnavailable as exc:
        log(f"{exc}: publishing from the calling thread")
        return FilteredLcm(url)

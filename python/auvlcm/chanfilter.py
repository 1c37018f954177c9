"""The kernel-side channel filter of an LCM udpm receive socket, from Python.

On one udpm group every socket receives the whole world's traffic, and liblcm
drops what nobody subscribed to only after its receive thread has woken for
it. The filter (c/common/lcm_chanfilter.c, in libauvlcm_sender.so) is a BPF
program on the instance's socket that drops those datagrams in the kernel, so
the process wakes only for the channels it subscribed to; lcm-spy and the
recorder still hear everything. Create it right after the lcm.LCM, before its
first subscribe or fileno(), and subscribe through subscribe() below: a
channel subscribed around it is dropped by the filter.
AUV_LCM_CHANFILTER=0 in the environment turns it off.
"""

from __future__ import annotations

import ctypes
import os
import sys
from typing import Any, Callable

import lcm

from auvlcm import own_socket
from auvlcm.paths import build_dir

_lib: ctypes.CDLL | None = None


def _load() -> ctypes.CDLL | None:
    global _lib
    if _lib is None:
        path = build_dir() / "lib" / "libauvlcm_sender.so"
        if not path.exists():
            return None
        lib = ctypes.CDLL(str(path), use_errno=True)
        p = ctypes.c_void_p
        lib.auv_chanfilter_new.argtypes = [ctypes.c_char_p]
        lib.auv_chanfilter_new.restype = p
        lib.auv_chanfilter_note.argtypes = [p, ctypes.c_char_p]
        lib.auv_chanfilter_note.restype = ctypes.c_int
        lib.auv_chanfilter_apply.argtypes = [p]
        lib.auv_chanfilter_apply.restype = ctypes.c_int
        lib.auv_chanfilter_free.argtypes = [p]
        lib.auv_chanfilter_free.restype = None
        own_socket.bind(lib)
        _lib = lib
    return _lib


class ChannelFilter:
    """The filter of one lcm.LCM(url) instance; does nothing when the URL is
    not udpm, the filter is turned off or the library is not built."""

    def __init__(self, url: str | None) -> None:
        self._lib = _load()
        self._h = self._lib.auv_chanfilter_new(url.encode() if url else None) if self._lib else None
        self.filtering = False
        self._told = False

    def subscribe(self, lc: Any, channel: str, handler: Callable[[str, bytes], None]) -> Any:
        """lc.subscribe(channel, handler) with the filter widened first."""
        if self._h is None:
            return lc.subscribe(channel, handler)
        if self._lib.auv_chanfilter_note(self._h, channel.encode()) < 0:
            raise MemoryError("channel filter: out of memory")
        sub = lc.subscribe(channel, handler)
        rc = self._lib.auv_chanfilter_apply(self._h)
        self.filtering = rc == 1
        if rc < 0 and not self._told:
            self._told = True
            err = os.strerror(ctypes.get_errno())
            print(f"lcm: the kernel refused the channel filter ({err}): receiving every channel", file=sys.stderr)
        return sub

    def close(self) -> None:
        if self._h is not None:
            self._lib.auv_chanfilter_free(self._h)
            self._h = None

    def __del__(self) -> None:
        self.close()


def _off(name: str) -> bool:
    return os.environ.get(name) == "0"


class FilteredLcm:
    """lcm.LCM(url) that wakes only for the channels subscribed through it.

    On a udpm url it receives on a socket of its own (auvlcm/own_socket.py:
    one wake-up per message instead of liblcm's two) and lcm.LCM only
    publishes; elsewhere, or with AUV_LCM_READER=0, liblcm receives behind a
    ChannelFilter. Everything else is the wrapped instance's."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self._own: own_socket.OwnReceiver | None = None
        lib = _load()
        if lib is not None and not _off("AUV_LCM_READER") and (url or "udpm://").startswith("udpm://"):
            try:
                self._own = own_socket.OwnReceiver(lib, url, filtering=not _off("AUV_LCM_CHANFILTER"))
            except OSError as exc:
                print(f"lcm: own socket on {url}: {exc}: liblcm receives", file=sys.stderr)
        self._filter = ChannelFilter(url) if self._own is None else None

    @property
    def filtering(self) -> bool:
        """The kernel drops the channels nobody here subscribed to."""
        return self._own.filtering if self._own is not None else bool(self._filter and self._filter.filtering)

    def subscribe(self, channel: str, handler: Callable[[str, bytes], None]) -> Any:
        if self._own is not None:
            return self._own.subscribe(channel, handler)
        return self._filter.subscribe(self.lc, channel, handler)

    def unsubscribe(self, sub: Any) -> None:
        if self._own is not None:
            self._own.unsubscribe(sub)
        else:
            self.lc.unsubscribe(sub)

    def fileno(self) -> int:
        return self._own.fd if self._own is not None else self.lc.fileno()

    def handle(self) -> None:
        if self._own is not None:
            self._own.handle()
        else:
            self.lc.handle()

    def handle_timeout(self, timeout_ms: int) -> int:
        if self._own is not None:
            return self._own.handle_timeout(timeout_ms)
        return self.lc.handle_timeout(timeout_ms)

    def handle_all(self, timeout_ms: int) -> int:
        """Waits up to timeout_ms for a message, then handles every one
        queued; how many."""
        if self._own is not None:
            return self._own.handle_all(timeout_ms)
        n = 0
        while self.lc.handle_timeout(timeout_ms if n == 0 else 0) > 0:
            n += 1
        return n

    def __getattr__(self, name: str) -> Any:
        if name in ("lc", "_filter", "_own"):  # not set yet: __init__ failed part-way
            raise AttributeError(name)
        return getattr(self.lc, name)

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


class FilteredLcm:
    """lcm.LCM(url) whose socket lets through only the channels subscribed
    through it; everything else is the wrapped instance's."""

    def __init__(self, url: str) -> None:
        self.lc = lcm.LCM(url)
        self._filter = ChannelFilter(url)

    def subscribe(self, channel: str, handler: Callable[[str, bytes], None]) -> Any:
        return self._filter.subscribe(self.lc, channel, handler)

    def __getattr__(self, name: str) -> Any:
        if name in ("lc", "_filter"):  # not set yet: __init__ failed part-way
            raise AttributeError(name)
        return getattr(self.lc, name)

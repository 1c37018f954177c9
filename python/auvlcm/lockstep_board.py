"""The lockstep clock's board of reports (c/common/lockstep_board.c), from Python.

A lockstep clock hears every participant's STEP_DONE of every step. On a
FilteredLcm that receives on its own socket, the board takes the ordinary
ones (a known participant's first report of a step) in C, in arrival order,
and Python handles only the rest; the clock asks the board who still owes a
step. attach() returns None where that cannot be (liblcm receives: then the
clock tracks every report in Python, as before).
"""

from __future__ import annotations

import ctypes
import functools
from typing import Any

from auvlcm import chanfilter

UNKNOWN = -(2**63)
_NAME = 256  # longer participant names are cut when listed (never when matched)


def _bind(lib: ctypes.CDLL) -> None:
    if getattr(lib, "_board_bound", False):
        return
    p, i64 = ctypes.c_void_p, ctypes.c_int64
    lib.lockstep_board_new.argtypes = [ctypes.c_char_p, ctypes.c_uint64]
    lib.lockstep_board_new.restype = p
    lib.lockstep_board_free.argtypes = [p]
    lib.lockstep_board_free.restype = None
    lib.lockstep_board_put.argtypes = [p, ctypes.c_char_p, i64]
    lib.lockstep_board_put.restype = ctypes.c_int
    lib.lockstep_board_remove.argtypes = [p, ctypes.c_char_p]
    lib.lockstep_board_remove.restype = None
    lib.lockstep_board_last_done.argtypes = [p, ctypes.c_char_p]
    lib.lockstep_board_last_done.restype = i64
    lib.lockstep_board_set_limit.argtypes = [p, i64]
    lib.lockstep_board_set_limit.restype = None
    lib.lockstep_board_owing.argtypes = [p, i64]
    lib.lockstep_board_owing.restype = ctypes.c_int
    lib.lockstep_board_owing_at.argtypes = [p, i64, ctypes.c_int, ctypes.c_char_p, ctypes.c_int]
    lib.lockstep_board_owing_at.restype = ctypes.c_int
    lib.lockstep_board_taken.argtypes = [p]
    lib.lockstep_board_taken.restype = i64
    lib.lockstep_board_take.argtypes = [p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int]
    lib.lockstep_board_take.restype = ctypes.c_int
    lib.lockstep_board_next.argtypes = [p, p, ctypes.c_void_p]
    lib.lockstep_board_next.restype = ctypes.c_int
    lib.lockstep_board_wait.argtypes = [p, p, ctypes.c_void_p, ctypes.c_int]
    lib.lockstep_board_wait.restype = ctypes.c_int
    lib.lockstep_board_set_watch.argtypes = [p, i64]
    lib.lockstep_board_set_watch.restype = None
    lib._board_bound = True


class LockstepBoard:
    """Participants and the last step each reported done, kept in C."""

    def __init__(self, lib: ctypes.CDLL, channel: str, fingerprint: bytes) -> None:
        _bind(lib)
        self._lib = lib
        self._b = lib.lockstep_board_new(channel.encode(), int.from_bytes(fingerprint, "big"))
        if not self._b:
            raise MemoryError("lockstep board: out of memory")
        self._owing = lib.lockstep_board_owing
        self._buf = ctypes.create_string_buffer(_NAME)

    @property
    def handle(self) -> int:
        return self._b

    def put(self, name: str, last_done: int) -> None:
        if self._lib.lockstep_board_put(self._b, name.encode(), last_done) < 0:
            raise MemoryError("lockstep board: out of memory")

    def remove(self, name: str) -> None:
        self._lib.lockstep_board_remove(self._b, name.encode())

    def last_done(self, name: str) -> int | None:
        v = self._lib.lockstep_board_last_done(self._b, name.encode())
        return None if v == UNKNOWN else v

    def set_limit(self, step: int) -> None:
        """Take reports of steps up to this one (the last published, plus one)."""
        self._lib.lockstep_board_set_limit(self._b, step)

    def set_watch(self, step: int) -> None:
        """The step the clock waits for: a wait returns when its last report came."""
        self._lib.lockstep_board_set_watch(self._b, step)

    def owing(self, step: int) -> int:
        """How many participants have not reported step."""
        return self._owing(self._b, step)

    def owing_names(self, step: int) -> list[str]:
        names = []
        while self._lib.lockstep_board_owing_at(self._b, step, len(names), self._buf, _NAME):
            names.append(self._buf.value.decode(errors="replace"))
        return names

    def take(self, channel: str, data: bytes) -> bool:
        """The board's decision on one message (what the reader does in C)."""
        return bool(self._lib.lockstep_board_take(self._b, channel.encode(), data, len(data)))

    @property
    def taken(self) -> int:
        return self._lib.lockstep_board_taken(self._b)

    def close(self) -> None:
        if self._b:
            self._lib.lockstep_board_free(self._b)
            self._b = None

    def __del__(self) -> None:
        self.close()


def attach(lc: Any, channel: str, fingerprint: bytes) -> LockstepBoard | None:
    """A board that takes its reports off lc's own socket before Python sees
    them; None when lc does not receive on a socket of its own."""
    own = getattr(lc, "_own", None)
    lib = chanfilter._load()
    if own is None or lib is None:
        return None
    board = LockstepBoard(lib, channel, fingerprint)
    own.read_with(
        functools.partial(lib.lockstep_board_next, board.handle),
        functools.partial(lib.lockstep_board_wait, board.handle),
        keep=board,
    )
    return board

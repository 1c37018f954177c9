"""A lockstep tracker whose last steps done live on a board in C.

The clock's reader lets the board (auvlcm/lockstep_board.py) take each
participant's ordinary report of its next step before Python sees it. This
tracker keeps everything else as LockstepTracker does (who takes part,
registrations, repeats, leaves) and keeps the board told: whom it knows and
what each has done. The steps done are read from the board, the one place
they are raised.
"""

from __future__ import annotations

from auvlcm.lockstep_board import LockstepBoard
from sim.multihil.lockstep import LockstepTracker


class BoardTracker(LockstepTracker):
    def __init__(self, board: LockstepBoard, timeout_s: float | None = 5.0, log=print) -> None:
        super().__init__(timeout_s=timeout_s, log=log)
        self.board = board

    def _sync_from_board(self, name: str) -> None:
        p = self.parts.get(name)
        done = self.board.last_done(name)
        if p is not None and done is not None and done > p.last_done:
            p.last_done = done

    def on_message(self, msg) -> None:
        self._sync_from_board(msg.participant)  # a repeat is judged against what the board took
        super().on_message(msg)
        p = self.parts.get(msg.participant)
        if p is None:
            self.board.remove(msg.participant)
        else:
            self.board.put(p.name, p.last_done)

    def remove(self, name: str) -> None:
        super().remove(name)
        self.board.remove(name)

    def owes(self, step: int) -> bool:
        return self.board.owing(step) > 0

    def waiting_for(self, step: int) -> list[str]:
        return sorted(self.board.owing_names(step))

    def missed_clock(self, step: int, since: float) -> bool:
        if self._newest_repeat <= since:
            return False
        return any(p.repeat_at > since and self.last_done(n) < step for n, p in self.parts.items())

    def last_done(self, name: str) -> int:
        """The participant's last step done (-1 before its first report)."""
        self._sync_from_board(name)
        p = self.parts.get(name)
        return p.last_done if p is not None else -1

    def drop_silent(self, step: int, since: float) -> None:
        if self.timeout_s is None:
            return
        super().drop_silent(step, since)
        for name in self.board.owing_names(step):
            if name not in self.parts:
                self.board.remove(name)

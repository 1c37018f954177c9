"""An lcm.LCM stand-in with no network, for running a process's loop in-process.

publish() keeps the messages (or drops them: keep=False), nothing ever
arrives; fileno() is a pipe nobody writes, so a loop that polls it for
incoming messages works unchanged. The simulator benchmark and the tests use
it to measure or record the simulator without LCM.
"""

from __future__ import annotations

import os


class _Subscription:
    def set_queue_capacity(self, n: int) -> None:
        pass


class OfflineLcm:
    def __init__(self, keep: bool = True) -> None:
        self._r, self._w = os.pipe()
        self.keep = keep
        self.published: list[tuple[str, bytes]] = []

    def publish(self, channel: str, data: bytes) -> None:
        if self.keep:
            self.published.append((channel, bytes(data)))

    def subscribe(self, channel: str, handler) -> _Subscription:
        return _Subscription()

    def unsubscribe(self, sub: _Subscription) -> None:
        pass

    def fileno(self) -> int:
        return self._r

    def handle(self) -> None:
        pass

    def close(self) -> None:
        """Release the pipe (the object is not used afterwards)."""
        if self._r >= 0:
            os.close(self._r)
            os.close(self._w)
            self._r = self._w = -1

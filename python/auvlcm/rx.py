"""Typed subscriptions that count and drop messages that fail to decode.

A bad message (another type on the channel, a truncated or corrupt payload)
never reaches the handler and never raises out of lc.handle(): it is counted
in the subscription's stats, and the first few are reported on stderr. A
message that decodes but that its handler cannot use (it raises: a value no
handler foresaw) is counted too (`handler_errors`, part of `decode_errors`:
"received, not usable") and reported the same way, instead of ending the
process with a traceback.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from typing import Any, Callable

import lcm

from auvlcm.decode import DecodeError, decode_strict

Handler = Callable[[str, Any], None]


@dataclass
class RxStats:
    received: int = 0
    delivered: int = 0
    wrong_fingerprint: int = 0
    malformed: int = 0
    handler_errors: int = 0
    last_error: str = ""

    @property
    def decode_errors(self) -> int:
        """Messages received and not usable: undecodable, or refused by their handler."""
        return self.wrong_fingerprint + self.malformed + self.handler_errors


@dataclass
class Subscription:
    channel: str
    msg_type: type
    handler: Handler
    stats: RxStats = field(default_factory=RxStats)
    lcm_sub: Any = None

    REPORT_FIRST = 3

    def on_raw(self, channel: str, data: bytes) -> None:
        self.stats.received += 1
        try:
            msg = decode_strict(self.msg_type, data)
        except DecodeError as exc:
            setattr(self.stats, exc.kind, getattr(self.stats, exc.kind) + 1)
            self.stats.last_error = str(exc)
            if self.stats.decode_errors <= self.REPORT_FIRST:
                print(f"lcm_rx: {channel}: dropped {len(data)}-byte message ({exc})", file=sys.stderr)
            return
        self.stats.delivered += 1
        try:
            self.handler(channel, msg)
        except Exception as exc:  # noqa: BLE001  (one message must not end the process)
            self.stats.handler_errors += 1
            self.stats.last_error = f"{type(exc).__name__}: {exc}"
            if self.stats.handler_errors <= self.REPORT_FIRST:
                tb = exc.__traceback__
                while tb is not None and tb.tb_next is not None:
                    tb = tb.tb_next
                where = f" at {tb.tb_frame.f_code.co_filename}:{tb.tb_lineno}" if tb else ""
                print(
                    f"lcm_rx: {channel}: dropped a message its handler could not use "
                    f"({type(exc).__name__}: {exc}{where})",
                    file=sys.stderr,
                )


class Receiver:
    """Owns typed subscriptions on one LCM instance."""

    def __init__(self, lc: lcm.LCM) -> None:
        self.lc = lc
        self.subscriptions: list[Subscription] = []
        self._retired_decode_errors = 0  # of subscriptions given up

    def subscribe(
        self, channel: str, msg_type: type, handler: Handler, queue_capacity: int | None = None
    ) -> Subscription:
        sub = Subscription(channel, msg_type, handler)
        sub.lcm_sub = self.lc.subscribe(channel, sub.on_raw)
        if queue_capacity is not None:
            sub.lcm_sub.set_queue_capacity(queue_capacity)
        self.subscriptions.append(sub)
        return sub

    def unsubscribe(self, sub: Subscription) -> None:
        self.lc.unsubscribe(sub.lcm_sub)
        # lcm's subscription object holds our handler and is invisible to the
        # garbage collector: drop it, or sub and its handler's owner never go
        sub.lcm_sub = None
        self.subscriptions.remove(sub)
        self._retired_decode_errors += sub.stats.decode_errors

    @property
    def decode_errors(self) -> int:
        return self._retired_decode_errors + sum(s.stats.decode_errors for s in self.subscriptions)

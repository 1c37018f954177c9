"""Read LCM logs (lcm-logger's format) with the project's types."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterator

import lcm

from auvlcm.decode import DecodeError, decode_strict
from auvlcm.types import type_of


@dataclass
class Event:
    timestamp: int      # the logging host's receive time [us] (not sim time)
    channel: str
    msg: Any            # decoded message, or None if it did not decode
    error: str = ""


# liblcm's udpm provider publishes this to itself when it starts; a logger on
# the same URL may record it. It is not one of our messages: skip it.
LCM_INTERNAL_CHANNELS = frozenset({"LCM_SELF_TEST"})


@dataclass
class LogStats:
    events: int = 0
    internal: int = 0   # liblcm's own traffic, skipped
    decoded: int = 0
    undecodable: int = 0
    per_channel: Counter = field(default_factory=Counter)


def read_events(path: str | Path, stats: LogStats | None = None) -> Iterator[Event]:
    """Every event of a log, decoded by fingerprint; failures come back with msg=None."""
    log = lcm.EventLog(str(path), "r")
    try:
        for ev in log:
            if ev.channel in LCM_INTERNAL_CHANNELS:
                if stats is not None:
                    stats.internal += 1
                continue
            if stats is not None:
                stats.events += 1
                stats.per_channel[ev.channel] += 1
            cls = type_of(ev.data)
            if cls is None:
                if stats is not None:
                    stats.undecodable += 1
                yield Event(ev.timestamp, ev.channel, None, "unknown fingerprint")
                continue
            try:
                msg = decode_strict(cls, ev.data)
            except DecodeError as exc:
                if stats is not None:
                    stats.undecodable += 1
                yield Event(ev.timestamp, ev.channel, None, str(exc))
                continue
            if stats is not None:
                stats.decoded += 1
            yield Event(ev.timestamp, ev.channel, msg)
    finally:
        log.close()

"""Read LCM logs (lcm-logger's format) with the project's types.

Events come from auvlcm.eventlog, which survives a damaged file: it skips a
bad header, resynchronises on the next valid one and counts what it skipped
(LogStats.damage). Tools print damage_lines() and exit EXIT_EVENTS_LOST when
events were lost (docs/tools.md).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterator

from auvlcm.decode import DecodeError, decode_strict
from auvlcm.eventlog import Damage, read_raw
from auvlcm.types import type_of


@dataclass
class Event:
    timestamp: int  # the logging host's receive time [us] (not sim time)
    channel: str
    msg: Any  # decoded message, or None if it did not decode
    error: str = ""


# liblcm's udpm provider publishes this to itself when it starts; a logger on
# the same URL may record it. It is not one of our messages: skip it.
LCM_INTERNAL_CHANNELS = frozenset({"LCM_SELF_TEST"})


@dataclass
class LogStats:
    events: int = 0
    internal: int = 0  # liblcm's own traffic, skipped
    decoded: int = 0
    undecodable: int = 0
    per_channel: Counter = field(default_factory=Counter)
    damage: Damage = field(default_factory=Damage)  # what a damaged file made us skip

    @property
    def events_lost(self) -> int:
        return self.damage.lost_events


# Exit status of a log tool whose log lost events to damage (after its output).
EXIT_EVENTS_LOST = 3


def damage_lines(path: str | Path, stats: LogStats) -> list[str]:
    """What was skipped reading the log, one line each (none for an intact log)."""
    return stats.damage.lines(path)


def _decodes(cls, data: bytes) -> bool:
    if cls is None:
        return False
    try:
        decode_strict(cls, data)
        return True
    except DecodeError:
        return False


def read_events(path: str | Path, stats: LogStats | None = None) -> Iterator[Event]:
    """Every readable event of a log, decoded by fingerprint; failures come back
    with msg=None; what a damaged file made us skip is in stats.damage."""
    stats = stats if stats is not None else LogStats()
    for ev in read_raw(path, stats.damage):
        cls = type_of(ev.data)
        if ev.suspect and not _decodes(cls, ev.data):  # its length was damaged, not garbage after it
            stats.damage.lost_events += 1
            continue
        if ev.channel in LCM_INTERNAL_CHANNELS:
            stats.internal += 1
            continue
        stats.events += 1
        stats.per_channel[ev.channel] += 1
        if cls is None:
            stats.undecodable += 1
            yield Event(ev.timestamp, ev.channel, None, "unknown fingerprint")
            continue
        try:
            msg = decode_strict(cls, ev.data)
        except DecodeError as exc:
            stats.undecodable += 1
            yield Event(ev.timestamp, ev.channel, None, str(exc))
            continue
        stats.decoded += 1
        yield Event(ev.timestamp, ev.channel, msg)

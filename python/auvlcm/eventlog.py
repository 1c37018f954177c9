"""Read lcm-logger's file format event by event, surviving damage.

An event is a 28-byte header, the channel name and the data:

    u32 sync 0xEDA1DA01 | i64 event number | i64 timestamp [us] | i32 channel length | i32 data length

(all big-endian; LCM's eventlog.c). liblcm's reader (lcm.EventLog) stops at
the first bad header, so one flipped byte mid-log silently dropped every
event after it. This reader checks every header (sync word, a channel length
of 1..MAX_CHANNEL bytes, a data length within the file) and that the next
event starts right after it (or the file ends there); a header that fails is
skipped by searching for the next sync word whose header passes the same
test. Event numbers must continue (see _Numbers). An event followed by garbage is kept when no valid header starts inside
it (the garbage is skipped) and marked suspect: its reader keeps it only if
it decodes exactly (auvlcm.log), else it counts as lost. What was skipped is counted: bytes, regions, and the events lost
(estimated from the event numbers on either side of a gap). Channel names
that are not UTF-8 are decoded with replacement characters and counted.
"""

from __future__ import annotations

import mmap
import struct
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

SYNC = 0xEDA1DA01
SYNC_BYTES = struct.pack(">I", SYNC)
HEADER = struct.Struct(">Iqqii")
MAX_CHANNEL = 255  # LCM allows 63 (LCM_MAX_CHANNEL_NAME_LENGTH); lcm-logger writes what it got


@dataclass
class RawEvent:
    number: int
    timestamp: int
    channel: str
    data: bytes
    offset: int
    bad_channel: bool = False
    suspect: bool = False  # garbage follows it: its length may be wrong (decode to be sure)


@dataclass
class Damage:
    """What a read skipped. lost_events > 0 means events were lost."""

    skipped_bytes: int = 0
    regions: list[tuple[int, int]] = field(default_factory=list)  # (offset, length) skipped
    lost_events: int = 0
    truncated: bool = False  # the file ends inside an event
    bad_channel_names: int = 0  # not UTF-8: kept, with U+FFFD in the name
    number_gaps: int = 0  # sound events whose numbers jump forward: whole events cut out

    @property
    def any(self) -> bool:
        return bool(self.skipped_bytes or self.lost_events or self.bad_channel_names)

    def lines(self, path: str | Path) -> list[str]:
        """What was skipped, one line each for stderr (none for an intact log)."""
        out = []
        if self.skipped_bytes:
            where = ", ".join(f"{o}+{n}" for o, n in self.regions[:5]) + (" ..." if len(self.regions) > 5 else "")
            out.append(
                f"{path}: damaged: skipped {self.skipped_bytes} byte(s) in {len(self.regions)} "
                f"region(s) (offset+length: {where}); about {self.lost_events} event(s) lost"
                + ("; the file ends inside an event" if self.truncated else "")
            )
        if self.number_gaps:
            out.append(
                f"{path}: the event numbers jump {self.number_gaps} time(s) between sound events "
                f"(whole events missing; {self.lost_events} event(s) lost in all)"
            )
        if self.bad_channel_names:
            out.append(
                f"{path}: {self.bad_channel_names} event(s) with a channel name that is not UTF-8 "
                "(kept, shown with U+FFFD)"
            )
        return out


class _Numbers:
    """Event number continuity. lcm-logger numbers events 0, 1, 2, ...; a forward
    jump that the next event confirms (it continues from the new number) means
    whole events were cut out. A single odd number (a damaged number field) or a
    restart from a lower one (logs joined) loses nothing."""

    def __init__(self, damage: Damage) -> None:
        self.damage, self.base, self.odd, self.after_skip = damage, -1, None, False

    def see(self, n: int) -> None:
        if self.base < 0 or self.after_skip:  # the gap before it was counted with the skip
            self.base, self.odd, self.after_skip = n, None, False
        elif self.odd is None:
            if n == self.base + 1:
                self.base = n
            else:
                self.odd = n
        else:
            odd, self.odd = self.odd, None
            if n == odd + 1 and odd > self.base + 1:  # confirmed: events base+1 .. odd-1 are missing
                self.damage.lost_events += odd - self.base - 1
                self.damage.number_gaps += 1
            self.base = n  # else a damaged number, or a restart


def _header_at(buf, pos: int, size: int, need_sync: bool = True) -> tuple[int, int, int, int] | None:
    """(number, timestamp, channel length, data length) of a plausible header at pos."""
    if pos + HEADER.size > size:
        return None
    sync, number, ts, clen, dlen = HEADER.unpack_from(buf, pos)
    if (need_sync and sync != SYNC) or not 0 < clen <= MAX_CHANNEL or number < 0 or dlen < 0:
        return None
    if pos + HEADER.size + clen + dlen > size:
        return None
    return number, ts, clen, dlen


def _chains(buf, pos: int, size: int, hdr) -> bool:
    """The event at pos ends at the end of the file or where the next sync word
    starts (that header is judged on its own when it is reached)."""
    end = pos + HEADER.size + hdr[2] + hdr[3]
    if end == size or buf[end : end + 4] == SYNC_BYTES[: min(4, size - end)]:
        return True
    nxt = _header_at(buf, end, size, need_sync=False)  # the next one's sync word damaged?
    if nxt is None:
        return False
    after = end + HEADER.size + nxt[2] + nxt[3]
    return after == size or buf[after : after + 4] == SYNC_BYTES[: min(4, size - after)]


def _resync(buf, start: int, size: int) -> int:
    """Offset of the next plausible, chaining header at or after start; size if none."""
    pos = start
    while True:
        pos = buf.find(SYNC_BYTES, pos, size)
        if pos < 0:
            return size
        hdr = _header_at(buf, pos, size)
        if hdr is not None and _chains(buf, pos, size, hdr):
            return pos
        pos += 1


def read_raw(path: str | Path, damage: Damage | None = None) -> Iterator[RawEvent]:
    """Every readable event of a log file, in order; what was skipped goes to damage."""
    damage = damage if damage is not None else Damage()
    with open(path, "rb") as f:
        size = f.seek(0, 2)
        if size == 0:
            return
        with mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as buf:
            pos, last_number = 0, -1
            numbers = _Numbers(damage)
            unpack, hsize = HEADER.unpack_from, HEADER.size
            while pos < size:
                if pos + hsize <= size:  # the common case, inline: a sound event followed by a sync word
                    sync, number, ts, clen, dlen = unpack(buf, pos)
                    end = pos + hsize + clen + dlen
                    if (
                        sync == SYNC
                        and 0 < clen <= MAX_CHANNEL
                        and number >= 0
                        and dlen >= 0
                        and (end == size or (end + 4 <= size and buf[end : end + 4] == SYNC_BYTES))
                    ):
                        raw_name = buf[pos + hsize : pos + hsize + clen]
                        try:
                            name, bad = raw_name.decode("utf-8"), False
                        except UnicodeDecodeError:
                            name, bad = raw_name.decode("utf-8", errors="replace"), True
                            damage.bad_channel_names += 1
                        numbers.see(number)
                        yield RawEvent(number, ts, name, buf[pos + hsize + clen : end], pos, bad)
                        last_number, pos = number, end
                        continue
                hdr = _header_at(buf, pos, size)
                suspect = hdr is not None and not _chains(buf, pos, size, hdr)
                if suspect:
                    # garbage after an intact event, or a wrong length? A wrong length
                    # runs over the next valid header; an intact event ends before it
                    if _resync(buf, pos + 1, size) < pos + HEADER.size + hdr[2] + hdr[3]:
                        hdr = None
                if hdr is None:
                    nxt = _resync(buf, pos + 1, size)
                    damage.skipped_bytes += nxt - pos
                    damage.regions.append((pos, nxt - pos))
                    after = _header_at(buf, nxt, size) if nxt < size else None
                    gap = after[0] - last_number - 1 if after is not None else -1
                    # lcm-logger numbers events from 0 without gaps: the numbers on either
                    # side count the events lost when they look sane (0: garbage only)
                    damage.lost_events += gap if 0 <= gap <= (nxt - pos) // HEADER.size + 1 else 1
                    if nxt >= size and _partial(buf, pos, size):
                        damage.truncated = True
                    numbers.after_skip = True
                    pos = nxt
                    continue
                number, ts, clen, dlen = hdr
                start = pos + HEADER.size
                raw_name = bytes(buf[start : start + clen])
                try:
                    name, bad = raw_name.decode("utf-8"), False
                except UnicodeDecodeError:
                    name, bad = raw_name.decode("utf-8", errors="replace"), True
                    damage.bad_channel_names += 1
                data = bytes(buf[start + clen : start + clen + dlen])
                numbers.see(number)
                yield RawEvent(number, ts, name, data, pos, bad, suspect)
                last_number = number
                pos = start + clen + dlen


def _partial(buf, pos: int, size: int) -> bool:
    """The skipped tail starts with a sync word: an event cut off by the end of the file."""
    return buf[pos : pos + 4] == SYNC_BYTES[: max(0, min(4, size - pos))]

"""The vehicle side of a radio transfer: chunks in, a verified whole out.

A command (a mission command, a plan load, a plugin upload) crosses the radio
as the command's own encoded LCM bytes cut into numbered chunks
(radio_chunk_t). The assembler keeps each partial transfer in a spool folder
(never where the managers' loader looks), so a dive, a dropped link or a
restart of the vehicle gateway resumes from the first chunk it lacks. It hands
the whole on only when every chunk is held and the SHA-256 of the whole
matches; the managers then apply their own checks (allowlist, the loader's).

Bad input is refused with a reason and counted, and nothing is written for
it: a chunk out of order or from another transfer (its header differs),
duplicated, beyond the declared count or size, for a channel the radio does
not carry, or a whole whose digest is wrong. Memory and disk are bounded: at
most MAX_TRANSFERS partial transfers of at most MAX_BYTES each, chunks held on
disk, and a transfer that stops arriving for `idle_expiry_s` is dropped
("never ending"). A dropped or refused transfer changes nothing on the vehicle.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
from collections import Counter, OrderedDict
from dataclasses import asdict, dataclass
from pathlib import Path

from auv import radio_chunk_t

CHANNELS = ("MISSION_CMD", "PLUGIN_UPLOAD")  # what the radio may publish on a vehicle
MAX_BYTES = 4 * 1024 * 1024  # a plugin or a plan: the managers take plans of 256 KiB
MAX_CHUNK_BYTES = 4096
MAX_CHUNKS = MAX_BYTES // 64  # a sender may not cut a whole into crumbs
MAX_TRANSFERS = 4
DONE_KEPT = 64  # finished transfer ids remembered, so a repeated last chunk is not run twice
HEX64 = re.compile(r"[0-9a-f]{64}")


@dataclass
class Header:
    """What every chunk of one transfer must agree on."""

    transfer_id: int
    vehicle: str
    channel: str
    count: int
    total_bytes: int
    sha256_hex: str


@dataclass
class Partial:
    header: Header
    next_index: int = 0
    held_bytes: int = 0
    last_s: float = 0.0


@dataclass
class Offer:
    """The answer to one chunk: what to acknowledge, and the whole when complete."""

    next_index: int
    state: str  # "holding", "done", "refused"
    reason: str = ""
    channel: str = ""
    data: bytes | None = None


class Assembler:
    def __init__(self, vehicle: str, spool: Path, idle_expiry_s: float = 3600.0) -> None:
        self.vehicle = vehicle
        self.spool = spool
        self.idle_expiry_s = idle_expiry_s
        self.partials: OrderedDict[int, Partial] = OrderedDict()
        self.done: OrderedDict[int, None] = OrderedDict()
        self.refused: Counter[str] = Counter()
        spool.mkdir(parents=True, exist_ok=True)
        self._load()

    # ------------------------------------------------------------ persistence
    def _paths(self, tid: int) -> tuple[Path, Path]:
        return self.spool / f"{tid}.part", self.spool / f"{tid}.json"

    def _save(self, p: Partial) -> None:
        _, meta = self._paths(p.header.transfer_id)
        tmp = meta.with_suffix(".tmp")
        tmp.write_text(json.dumps({"header": asdict(p.header), "next_index": p.next_index, "held": p.held_bytes}))
        os.replace(tmp, meta)  # the data is appended first: a restart truncates it to what the meta says

    def _save_done(self) -> None:
        tmp = self.spool / "done.tmp"
        tmp.write_text(json.dumps(list(self.done)))
        os.replace(tmp, self.spool / "done.json")

    def _load(self) -> None:
        done = self.spool / "done.json"
        if done.is_file():
            try:
                self.done = OrderedDict((int(t), None) for t in json.loads(done.read_text())[-DONE_KEPT:])
            except (ValueError, TypeError):
                self.refused["spool: unreadable done list"] += 1
        for meta in sorted(self.spool.glob("*.json")):
            if meta.name == "done.json":
                continue
            try:
                d = json.loads(meta.read_text())
                p = Partial(Header(**d["header"]), int(d["next_index"]), int(d["held"]))
                data = meta.with_suffix(".part")
                with data.open("r+b") as f:
                    f.truncate(p.held_bytes)
            except (OSError, ValueError, TypeError, KeyError):
                self.refused["spool: unreadable partial transfer"] += 1
                self._forget(int(meta.stem) if meta.stem.isdigit() else -1, meta)
                continue
            if len(self.partials) < MAX_TRANSFERS:
                self.partials[p.header.transfer_id] = p
            else:
                self._forget(p.header.transfer_id)

    def _forget(self, tid: int, meta: Path | None = None) -> None:
        self.partials.pop(tid, None)
        for path in (*self._paths(tid), meta):
            if path is not None:
                path.unlink(missing_ok=True)

    # ------------------------------------------------------------ the protocol
    def holding(self) -> list[tuple[int, int]]:
        """(transfer id, next index) of every partial transfer: sent home at the surface."""
        return [(t, p.next_index) for t, p in self.partials.items()]

    def expire(self, now_s: float) -> list[int]:
        """Drop the partial transfers nothing arrived for in idle_expiry_s."""
        old = [t for t, p in self.partials.items() if now_s - p.last_s > self.idle_expiry_s]
        for t in old:
            self.refused["never ended: expired"] += 1
            self._forget(t)
        return old

    def _refuse(self, key: str, reason: str, next_index: int, final: bool = False) -> Offer:
        self.refused[key] += 1
        return Offer(next_index, "refused" if final else "holding", reason)

    def offer(self, c: radio_chunk_t, now_s: float) -> Offer:
        tid = c.transfer_id
        if tid in self.done:
            self.refused["duplicate"] += 1
            return Offer(c.count, "done", "duplicate: transfer already delivered")
        p = self.partials.get(tid)
        bad = self._check_header(c)
        if bad:  # one bad chunk never costs a transfer held so far
            return self._refuse(bad[0], bad[1], p.next_index if p else 0, final=p is None)
        head = Header(tid, c.vehicle, c.channel, c.count, c.total_bytes, c.sha256_hex)
        if p is None:
            if c.index != 0:
                return self._refuse("unknown transfer", f"chunk {c.index} of a transfer not held: send from 0", 0)
            self.expire(now_s)
            if len(self.partials) >= MAX_TRANSFERS:
                return self._refuse("busy", f"{MAX_TRANSFERS} transfers already in progress: try later", 0, final=True)
            p = Partial(head)
            self.partials[tid] = p
            self._paths(tid)[0].write_bytes(b"")
        elif p.header != head:
            return self._refuse(
                "another transfer", f"chunk {c.index} does not match transfer {tid}'s header", p.next_index
            )
        p.last_s = now_s
        if c.index < p.next_index:
            return self._refuse("duplicate", f"duplicate chunk {c.index}", p.next_index)
        if c.index > p.next_index:
            return self._refuse("out of order", f"chunk {c.index} out of order: expected {p.next_index}", p.next_index)
        n, held = c.n_bytes, p.held_bytes
        if len(c.data) != n or not 0 < n <= MAX_CHUNK_BYTES:
            return self._refuse("bad chunk", f"chunk {c.index}: {n} bytes", p.next_index)
        if held + n > c.total_bytes:
            return self._refuse(
                "too many", f"chunk {c.index} goes past the declared {c.total_bytes} bytes", p.next_index
            )
        if c.index == c.count - 1 and held + n != c.total_bytes:
            return self._refuse("too few", f"{held + n} of {c.total_bytes} bytes at the last chunk", p.next_index)
        data_path, _ = self._paths(tid)
        with data_path.open("ab") as f:
            f.write(c.data)
        p.next_index += 1
        p.held_bytes += c.n_bytes
        if p.next_index < c.count:
            self._save(p)
            return Offer(p.next_index, "holding")
        whole = data_path.read_bytes()
        self._forget(tid)
        if hashlib.sha256(whole).hexdigest() != c.sha256_hex:
            return self._refuse("wrong digest", "the whole does not match its SHA-256: dropped", 0, final=True)
        self.done[tid] = None
        while len(self.done) > DONE_KEPT:
            self.done.popitem(last=False)
        self._save_done()
        return Offer(p.next_index, "done", channel=c.channel, data=whole)

    def _check_header(self, c: radio_chunk_t) -> tuple[str, str] | None:
        if c.vehicle != self.vehicle:
            return "wrong vehicle", f"addressed to {c.vehicle!r}, this is {self.vehicle}"
        if c.channel not in CHANNELS:
            return "channel", f"channel {c.channel!r} is not carried (only {', '.join(CHANNELS)})"
        if not HEX64.fullmatch(c.sha256_hex):
            return "bad digest", "sha256_hex is not 64 lowercase hex digits"
        if not 0 < c.total_bytes <= MAX_BYTES:
            return "too large", f"{c.total_bytes} bytes: at most {MAX_BYTES}"
        if not 0 < c.count <= min(MAX_CHUNKS, c.total_bytes):
            return "too many", f"{c.count} chunks for {c.total_bytes} bytes"
        if c.count * MAX_CHUNK_BYTES < c.total_bytes:
            return "too few", f"{c.count} chunks cannot hold {c.total_bytes} bytes"
        if not 0 <= c.index < c.count:
            return "too many", f"chunk {c.index} of {c.count}"
        return None

"""The shore side of a radio transfer: commands cut into chunks, sent while the
link is up, resumed from what the vehicle says it holds.

One Outbox per vehicle. Each command is a Transfer of its opaque encoded LCM
bytes (never decoded and rebuilt: a signature the operator's tool appended
passes through untouched). The link counts as up while the vehicle was heard
within `link_timeout_s` (its acks and reports come back over the same radio).
Sending is go-back-N: at most `window` chunks beyond the last one the vehicle
acknowledged, and after `retry_s` without progress the chunks from that one
again (the wait doubling at each retry without progress, up to 16 x; back to
`retry_s`, from what the vehicle holds, when it is heard again after a
silence: it surfaced). A vehicle report lists the partial transfers it holds, so after a dive
or a restart of either side the shore resumes from the first chunk missing.
One transfer is sent at a time, in queue order: a short command never waits
behind a long plugin for more than the current transfer, and it is expired
after `expiry_s` if never delivered: then nothing changed on the vehicle.
"""

from __future__ import annotations

import hashlib
import secrets
from collections import deque
from dataclasses import dataclass, field

from auv import radio_ack_t, radio_chunk_t
from auv import radio_command_status_t as cs

MAX_QUEUE = 64  # commands waiting per vehicle; more are refused at the shore
MAX_URGENT = 16  # abort, pause, resume: taken beyond a queue full of plans and plugins


@dataclass
class Transfer:
    tid: int
    vehicle: str
    channel: str
    data: bytes
    seq: int
    what: str
    created_s: float
    expiry_s: float
    chunk_bytes: int
    digest: str = ""
    state: int = cs.STATE_QUEUED
    acked: int = 0  # the first chunk the vehicle lacks
    next_send: int = 0
    last_progress_s: float = 0.0
    backoff: int = 0  # retries since the last progress: each waits twice as long
    message: str = ""
    route: str = "radio"
    changed: bool = True  # a status is due

    def __post_init__(self) -> None:
        self.digest = hashlib.sha256(self.data).hexdigest()

    @property
    def count(self) -> int:
        return max(1, -(-len(self.data) // self.chunk_bytes))

    def held_bytes(self) -> int:
        return min(len(self.data), self.acked * self.chunk_bytes)

    def chunk(self, index: int, utime: int) -> radio_chunk_t:
        c = radio_chunk_t()
        c.utime, c.transfer_id, c.vehicle, c.channel = utime, self.tid, self.vehicle, self.channel
        c.index, c.count, c.total_bytes, c.sha256_hex = index, self.count, len(self.data), self.digest
        c.data = self.data[index * self.chunk_bytes : (index + 1) * self.chunk_bytes]
        c.n_bytes = len(c.data)
        return c

    def status(self, utime: int) -> cs:
        m = cs()
        m.utime, m.vehicle, m.transfer_id, m.channel, m.seq, m.what = (
            utime,
            self.vehicle,
            self.tid,
            self.channel,
            self.seq,
            self.what,
        )
        m.state, m.route, m.bytes_total, m.bytes_held, m.message = (
            self.state,
            self.route,
            len(self.data),
            self.held_bytes(),
            self.message,
        )
        return m

    def set(self, state: int, message: str = "") -> None:
        if state != self.state or message != self.message:
            self.state, self.message, self.changed = state, message, True


@dataclass
class Outbox:
    vehicle: str
    chunk_bytes: int = 512
    window: int = 8
    retry_s: float = 2.0
    link_timeout_s: float = 3.0
    expiry_s: float = 3600.0
    queue: deque[Transfer] = field(default_factory=deque)
    finished: deque[Transfer] = field(default_factory=lambda: deque(maxlen=64))
    heard_s: float = -1e18

    def submit(self, channel: str, data: bytes, seq: int, what: str, now_s: float, urgent: bool = False) -> Transfer:
        """Queue a command (urgent: before everything not yet in flight)."""
        if len(self.queue) >= MAX_QUEUE + (MAX_URGENT if urgent else 0):
            raise OverflowError(f"{self.vehicle}: {MAX_QUEUE} commands already queued")
        t = Transfer(
            secrets.randbits(62) or 1, self.vehicle, channel, data, seq, what, now_s, self.expiry_s, self.chunk_bytes
        )
        if urgent:
            self.queue.insert(sum(1 for x in self.queue if x.state == cs.STATE_IN_FLIGHT), t)
        else:
            self.queue.append(t)
        return t

    def link_up(self, now_s: float) -> bool:
        return now_s - self.heard_s <= self.link_timeout_s

    def heard(self, now_s: float, holding: dict[int, int] | None = None) -> None:
        """The vehicle was heard; with its report, the partial transfers it holds."""
        if not self.link_up(now_s):  # back from a dive: what was on the air then is lost
            for t in self.queue:
                if t.state == cs.STATE_IN_FLIGHT:
                    t.next_send, t.backoff, t.last_progress_s = t.acked, 0, now_s
        self.heard_s = now_s
        if holding is None:
            return
        # A report is a snapshot that may be older than the last ack: it only moves a
        # transfer forward. A vehicle that holds less than acknowledged (it lost its
        # spool) says so in its answer to the next chunk, and on_ack goes back.
        for t in self.queue:
            if holding.get(t.tid, -1) > t.acked:
                t.acked = t.next_send = holding[t.tid]
                t.changed = True

    def on_ack(self, ack: radio_ack_t, now_s: float) -> Transfer | None:
        self.heard(now_s)
        t = next((x for x in self.queue if x.tid == ack.transfer_id), None)
        if t is None:
            return None
        if ack.state == radio_ack_t.STATE_DONE:
            t.acked = t.count
            t.set(cs.STATE_DELIVERED)
            self._finish(t)
        elif ack.state == radio_ack_t.STATE_REFUSED:
            t.set(cs.STATE_REFUSED, ack.reason)
            self._finish(t)
        elif 0 <= ack.next_index <= t.count:
            if ack.next_index > t.acked:
                t.last_progress_s, t.changed, t.backoff = now_s, True, 0
                t.acked, t.next_send = ack.next_index, max(t.next_send, ack.next_index)
            elif ack.next_index < t.acked:  # it holds less than it said (restarted): resend from there
                t.acked = t.next_send = ack.next_index
                t.changed = True
        return t

    def _finish(self, t: Transfer) -> None:
        if t in self.queue:
            self.queue.remove(t)
        self.finished.append(t)

    def on_manager_ack(self, seq: int, text: str) -> Transfer | None:
        t = next((x for x in reversed(self.finished) if x.seq == seq and x.state >= cs.STATE_DELIVERED), None)
        if t is not None and t.state in (cs.STATE_DELIVERED, cs.STATE_ACKNOWLEDGED) and text not in t.message:
            t.set(cs.STATE_ACKNOWLEDGED, (t.message + "; " if t.message else "") + text)  # one per manager
        return t

    def due(self, now_s: float, utime: int) -> list[radio_chunk_t]:
        """Chunks to hand to the radio now; expires what waited too long."""
        for t in list(self.queue):
            if now_s - t.created_s > t.expiry_s:
                t.set(cs.STATE_EXPIRED, f"not delivered within {t.expiry_s:g} s: nothing changed on the vehicle")
                self._finish(t)
        if not self.queue or not self.link_up(now_s):
            return []
        t = self.queue[0]
        if t.state == cs.STATE_QUEUED:
            t.set(cs.STATE_IN_FLIGHT)
            t.last_progress_s = now_s
        # Go back to what the vehicle holds after retry_s without progress, then after
        # twice that, ... (up to 16 x): what was sent may still wait in the radio's queue,
        # and resending it at a fixed pace can fill that queue with copies faster than
        # the air empties it (the transfer then stalls behind its own duplicates).
        if now_s - t.last_progress_s > self.retry_s * (1 << t.backoff):
            t.next_send, t.last_progress_s, t.backoff = t.acked, now_s, min(t.backoff + 1, 4)
        out = []
        while t.next_send < min(t.count, t.acked + self.window):
            out.append(t.chunk(t.next_send, utime))
            t.next_send += 1
        return out

    def statuses(self, utime: int) -> list[cs]:
        out = []
        for t in (*self.queue, *self.finished):
            if t.changed:
                t.changed = False
                out.append(t.status(utime))
        return out

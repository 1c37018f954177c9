"""What crosses the radio, and the clock the gateways keep.

A radio frame's payload is one encoded LCM message of the radio protocol
(radio_chunk_t, radio_ack_t, radio_report_t) or a manager's mission_ack_t
relayed home; the receiver tells them apart by the fingerprint (its first 8
bytes) and drops anything else, counted.
"""

from __future__ import annotations

import time
from typing import Any

import lcm

from auv import mission_ack_t, radio_ack_t, radio_chunk_t, radio_frame_t, radio_report_t, sim_clock_t
from auvlcm.decode import DecodeError, decode_strict

# The largest command the vehicle's gateway takes (auv-radio, RA_MAX_BYTES in
# c/drivers/radio/radio_asm.h): a plugin or a plan; the shore refuses more at once.
MAX_BYTES = 4 * 1024 * 1024

PAYLOAD_TYPES = {c._get_packed_fingerprint(): c for c in (radio_chunk_t, radio_ack_t, radio_report_t, mission_ack_t)}


def payload(data: bytes) -> Any:
    """The protocol message in a frame's payload; DecodeError if it is none."""
    cls = PAYLOAD_TYPES.get(bytes(data[:8]))
    if cls is None:
        raise DecodeError("not a radio protocol message", "wrong_fingerprint")
    return decode_strict(cls, bytes(data))


def frame(src: str, dst: str, seq: int, utime: int, data: bytes) -> bytes:
    f = radio_frame_t()
    f.utime, f.src, f.dst, f.seq, f.n_bytes, f.payload = utime, src, dst, seq, len(data), data
    return f.encode()


class Clock:
    """SIM.CLOCK's time (--clock sim: None until the first), or this machine's."""

    def __init__(self, lc: lcm.LCM, sim: bool) -> None:
        self.sim = sim
        self.t: float | None = None
        if sim:
            lc.subscribe("SIM\\.CLOCK", self._on_clock)

    def _on_clock(self, channel: str, data: bytes) -> None:
        try:
            t = decode_strict(sim_clock_t, data).utime * 1e-6
        except DecodeError:
            return
        if self.t is None or t > self.t:
            self.t = t

    def now(self) -> float | None:
        return self.t if self.sim else time.time()

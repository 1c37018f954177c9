"""The serial line's timing: when each byte of a device's output is on the far end.

A UART sends 10 bits a byte (start, 8 data, stop), so at `baud` a byte takes
10 / baud seconds and a burst of n bytes occupies the line for n * 10 / baud s.
Everything here is in sim time: a burst is queued at the sim time of its
measurement, starts when the line is free (a device cannot send two messages at
once), and byte k (from 0) is complete at start + (k + 1) * 10 / baud.

How sim time becomes wall time is the port's clock (sim.devices.clocks); this
module is pure arithmetic, the same in every clock mode.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

BITS_PER_BYTE = 10  # start bit, 8 data bits, stop bit (8N1)
# the rates a configuration may name (wire.baud)
BAUDS = (1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600)


def byte_time_s(baud: int) -> float:
    """Seconds one byte occupies the line at baud."""
    return BITS_PER_BYTE / baud


@dataclass
class Burst:
    """One message on the line: its bytes and when they go."""

    data: bytes
    t_measured: float  # sim time of the measurement it encodes
    t_start: float  # sim time its first bit leaves the device
    byte_s: float  # seconds per byte
    sent: int = 0  # bytes handed to the port so far

    @property
    def t_end(self) -> float:
        """Sim time its last byte is complete at the far end."""
        return self.t_start + len(self.data) * self.byte_s

    def due(self, horizon: float) -> int:
        """How many of its bytes are complete by sim time horizon."""
        if horizon < self.t_start:
            return 0
        n = math.floor((horizon - self.t_start) / self.byte_s + 1e-9)
        return min(max(n, 0), len(self.data))

    def next_byte_t(self) -> float:
        """Sim time the next unsent byte is complete (inf when all are sent)."""
        return self.t_start + (self.sent + 1) * self.byte_s if self.sent < len(self.data) else math.inf


@dataclass
class Line:
    """A device's output line: bursts follow one another at the line's rate."""

    baud: int
    free_at: float = -math.inf  # sim time the last queued burst ends

    @property
    def byte_s(self) -> float:
        return byte_time_s(self.baud)

    def burst(self, data: bytes, t_measured: float, now: float) -> Burst:
        """The burst of data measured at t_measured, queued at sim time now: it starts
        at the latest of the measurement, the end of the line's previous burst and now
        (bytes never leave before they are written)."""
        b = Burst(bytes(data), t_measured, max(t_measured, self.free_at, now), self.byte_s)
        self.free_at = b.t_end
        return b

    def duration_s(self, n_bytes: int) -> float:
        """Seconds n_bytes occupy the line."""
        return n_bytes * self.byte_s

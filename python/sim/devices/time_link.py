"""The time link: the simulator's clock on a line to a vehicle computer (HIL at the wire).

At the wire the vehicle computer has its own LCM world and sees the simulator
only through device links; its managers, auv-nav and drivers run on
`--clock sim` and need a SIM.CLOCK there. This link carries it: one sentence
per period (`time_link.rate_hz`, sim time),

    $PAUVT,<sim time [us], integer>,<warp>*hh\\r\\n

whose time is the sim time at which its own LAST byte is complete at the far
end. The emulator knows the line's timing (sim.devices.line): the sentence
starts when the line is free and not before now, and ends len x 10 / baud
later; nothing else is on the line, so it starts at once. The driver
(c/drivers/timesync, `auv-timesync`) therefore publishes the time it reads as
it is: a reader's stamp needs no line-delay correction. `warp` is sim seconds
per wall second (1 real time; 0 a simulator as fast as the CPU allows).

Configured by the top-level `time_link:` section (sim.time_link; docs/simulator.md,
"The time link"): no sensor polls it.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from sim.devices.emulator import Emulator
from sim.devices.nmea import sentence

# the longest sentence the link writes: 16 digits of time (past 2100: refused
# by the driver anyway), a warp of %.6g (up to 12 characters), the frame
SENTENCE_MAX_BYTES = len("$PAUVT,,*hh\r\n") + 16 + 12


class Sample(NamedTuple):
    """What the time link 'measures': when its sentence starts on the line, and the warp."""

    t_start: float  # sim time of the sentence's first bit [s]
    warp: float
    byte_s: float  # the line's seconds per byte


def pauvt(utime_us: int, warp: float) -> bytes:
    """$PAUVT,<utime>,<warp>*hh CR LF (warp as %.6g: 1, 10, 0.25)."""
    return sentence("PAUVT", [str(utime_us), f"{warp:.6g}"])


def stamped_sentence(t_start: float, warp: float, byte_s: float) -> bytes:
    """The sentence whose time is that of its own last byte: t_start + len x byte_s
    (its length depends on its digits: settled in two or three rounds)."""
    data = pauvt(round(t_start * 1e6), warp)
    for _ in range(4):
        t_end = round((t_start + len(data) * byte_s) * 1e6)
        again = pauvt(t_end, warp)
        if len(again) == len(data):
            return again
        data = again
    return data  # pragma: no cover - the length settles in two rounds


class TimeLink(Emulator):
    sensor = "time_link"
    protocol = "pauvt"

    def encode(self, msg: Sample, truth: Any) -> list[bytes]:
        return [stamped_sentence(msg.t_start, msg.warp, msg.byte_s)]

"""A vehicle's modem on the sending side: size and rate limits, then the water.

The modem sends one frame at a time: a frame keeps it busy for
frame_overhead_s + 8 * n_bytes / bitrate_bps, and a frame offered while it is
busy (or sooner than min_interval_s after the last start) is refused, not
queued, so the vehicle software sees at once (on <VEHICLE>.MODEM_STATUS)
that it asked for more than the link carries.
"""

from __future__ import annotations

from auv import acoustic_frame_t, modem_status_t, modem_tx_t
from sim.modem.acoustics import frame_duration_s
from sim.modem.config import ModemConfig
from sim.sensors.base import utime

KINDS = (modem_tx_t.KIND_RAW, modem_tx_t.KIND_NAV_REPORT, modem_tx_t.KIND_TEAM)


class Transmitter:
    def __init__(self, cfg: ModemConfig, vehicle: str, status: modem_status_t) -> None:
        self.cfg = cfg
        self.vehicle = vehicle
        self.status = status  # counters shared with the receiving side
        self.busy_until = float("-inf")  # sim time the current frame ends
        self.busy_seq = 0
        self.last_start = float("-inf")

    def refuse(self, counter: str, seq: int, reason: str) -> str:
        setattr(self.status, counter, getattr(self.status, counter) + 1)
        self.status.last_refused_seq = seq
        self.status.last_refusal = reason
        return reason

    def check(self, t: float, msg: modem_tx_t) -> str:
        """Why the frame cannot be sent at sim time t ("" if it can)."""
        cfg, seq = self.cfg, msg.seq
        if msg.vehicle not in ("", self.vehicle):
            return self.refuse(
                "refused_invalid", seq, f"vehicle {msg.vehicle!r} is not this modem's vehicle {self.vehicle!r}"
            )
        if msg.kind not in KINDS:
            return self.refuse("refused_invalid", seq, f"unknown kind {msg.kind}")
        if msg.dst_vehicle == self.vehicle:
            return self.refuse("refused_invalid", seq, "addressed to itself")
        if msg.n_bytes <= 0:
            return self.refuse("refused_invalid", seq, "empty frame")
        if msg.n_bytes > cfg.max_frame_bytes:
            return self.refuse(
                "refused_size", seq, f"{msg.n_bytes} bytes is over max_frame_bytes = {cfg.max_frame_bytes}"
            )
        if t < self.busy_until - 1e-9:
            return self.refuse(
                "refused_rate", seq, f"busy: frame {self.busy_seq} is on the air until t = {self.busy_until:.3f} s"
            )
        if t - self.last_start < cfg.min_interval_s - 1e-9:
            return self.refuse(
                "refused_rate",
                seq,
                f"min_interval_s = {cfg.min_interval_s:g}: last frame started at t = {self.last_start:.3f} s",
            )
        return ""

    def send(self, t: float, position: tuple[float, float, float], msg: modem_tx_t) -> acoustic_frame_t | str:
        """The frame in the water (for SIM.ACOUSTIC), or the reason it was refused."""
        reason = self.check(t, msg)
        if reason:
            return reason
        duration = frame_duration_s(msg.n_bytes, self.cfg)
        self.busy_until = t + duration
        self.busy_seq = msg.seq
        self.last_start = t
        self.status.sent += 1
        self.status.busy_until_utime = utime(self.busy_until)
        f = acoustic_frame_t()
        f.utime = utime(t)
        f.tx_north_m, f.tx_east_m, f.tx_depth_m = position
        f.source_level_db = self.cfg.source_level_db
        f.duration_us = utime(duration)
        f.src_vehicle, f.dst_vehicle, f.seq, f.kind = self.vehicle, msg.dst_vehicle, msg.seq, msg.kind
        f.n_bytes, f.payload = msg.n_bytes, bytes(msg.payload)
        return f

"""A vehicle's modem on the receiving side: when and whether a frame arrives.

A frame sent at t0 from P arrives at the first physics step t at which its
wavefront, a sphere of radius c * (t - t0), has reached the receiver's true
position p(t); its arrival time is t0 + |p(t) - P| / c, with c the mean sound
speed between the two depths. Receiver motion during the flight is thus
accounted for, and the step that delivers the frame is at most one physics
step after the arrival time. Beyond max_range_m the frame is never
delivered; within it, the range curve and a seeded draw decide (acoustics.py).
"""

from __future__ import annotations

from auv import acoustic_frame_t, modem_rx_t, modem_status_t

from sim.config import VEHICLE_ID
from sim.environment import Environment
from sim.modem.acoustics import distance_3d, loss_probability, snr_db, uniform_draw
from sim.modem.config import ModemConfig
from sim.sensors.base import utime

EPS_M = 1e-6
# A frame whose wavefront is a gap g short of us cannot arrive within
# g / (2 c): the sound speed along the path and the receiver's speed would
# have to double the closing rate. Frames are looked at again only then, so
# a frame in flight costs a few checks instead of one per physics step.
CLOSING_MARGIN = 2.0


class Receiver:
    def __init__(self, cfg: ModemConfig, vehicle: str, seed: int, env: Environment,
                 status: modem_status_t) -> None:
        self.cfg = cfg
        self.vehicle = vehicle
        self.seed = seed
        self.env = env
        self.status = status
        self.pending: list[acoustic_frame_t] = []
        self._next_check: dict[int, float] = {}  # id(frame) -> sim time to look again
        self.bad_frames = 0             # from no valid vehicle id: dropped

    def hear(self, frame: acoustic_frame_t) -> None:
        """A frame entered the water somewhere: track it if it is meant for us."""
        if not VEHICLE_ID.fullmatch(frame.src_vehicle):
            self.bad_frames += 1
            return
        if frame.src_vehicle == self.vehicle:
            return                      # a modem does not hear itself
        if frame.dst_vehicle and frame.dst_vehicle != self.vehicle:
            return                      # addressed to another vehicle
        self.pending.append(frame)

    def step(self, t: float, position: tuple[float, float, float]) -> list[modem_rx_t]:
        """Frames whose wavefront reached us by sim time t, lost ones left out."""
        arrived, waiting = [], []
        for f in self.pending:
            if t < self._next_check.get(id(f), t):
                waiting.append(f)
                continue
            tx_pos = (f.tx_north_m, f.tx_east_m, f.tx_depth_m)
            c = self.env.mean_sound_speed(f.tx_depth_m, position[2])
            d = distance_3d(tx_pos, position)
            gap = d - c * (t - f.utime / 1e6)
            if gap <= EPS_M:
                arrived.append((f.utime / 1e6 + d / c, f, d))
                self._next_check.pop(id(f), None)
            else:
                waiting.append(f)
                self._next_check[id(f)] = t + gap / (CLOSING_MARGIN * c)
        self.pending = waiting
        out = []
        for t_arr, f, d in sorted(arrived, key=lambda a: (a[0], a[1].src_vehicle, a[1].seq)):
            if d > self.cfg.max_range_m:
                self.status.out_of_range += 1
                continue
            u = uniform_draw(self.seed, f.src_vehicle, f.seq, f.utime, self.vehicle)
            if u < loss_probability(d, self.cfg):
                self.status.lost += 1
                continue
            self.status.received += 1
            out.append(self._rx_message(t_arr, f, d))
        return out

    def _rx_message(self, t_arr: float, f: acoustic_frame_t, d: float) -> modem_rx_t:
        m = modem_rx_t()
        m.utime, m.vehicle, m.src_vehicle, m.dst_vehicle = utime(t_arr), self.vehicle, f.src_vehicle, f.dst_vehicle
        m.seq, m.kind, m.tx_utime = f.seq, f.kind, f.utime
        m.range_m, m.snr_db = d, snr_db(d, f.source_level_db, self.cfg)
        m.n_bytes, m.payload = f.n_bytes, bytes(f.payload)
        return m

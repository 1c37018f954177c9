"""A vehicle's modem on the receiving side: when and whether a frame arrives.

A frame sent at t0 from P arrives at the first physics step t at which its
wavefront, a sphere of radius c * (t - t0), has reached the receiver's true
position p(t); its arrival time is t0 + |p(t) - P| / c, with c the mean sound
speed along the straight path (Environment.path_sound_speed: the linear
profile's between the two depths, or the ocean's harmonic mean along it). Receiver motion during the flight is thus
accounted for. Beyond max_range_m the frame is never delivered; within it,
the range curve and a seeded draw decide (acoustics.py).

The arrival is solved on the receiver's track (track.py: its true position
at every physics step), not at the step that happens to be running when the
frame is looked at, and a frame is judged only once the simulator's time has
passed a horizon (`judge(horizon)`): everything stamped up to the horizon is
certain to have reached this simulator by then. Under lockstep the node sets
the horizon two clock steps back (node.py), so a rerun judges the same frames
at the same steps with the same positions whatever order the processes ran
in; free-running, the horizon is the current step.

The receiver hears one frame at a time, and not while it sends. A frame
occupies a receiver over its reception interval [arrival, arrival + duration]
(duration = the sender's time on the air). Two frames whose intervals overlap
there are both lost (`collided`), whoever they were addressed to; a frame
whose interval overlaps one of this modem's own transmissions is lost
(`deaf`). Both are decided from the frames' times alone, when a frame
arrives: against frames already heard, against frames still in the water
(their arrival predicted from our position at the horizon; such a frame is
then marked and lost on arrival too) and against our own transmissions. The
one case this misses: a frame sent after an earlier one began to arrive
here, that arrives while the earlier one is still being heard, is lost, but
the earlier one was delivered at its first bit and stays delivered (the same
for our own transmission starting during a reception).
"""

from __future__ import annotations

from auv import acoustic_frame_t, modem_rx_t, modem_status_t
from sim.config import VEHICLE_ID
from sim.environment import Environment
from sim.modem.acoustics import distance_3d, loss_probability, snr_db, uniform_draw
from sim.modem.config import ModemConfig
from sim.modem.track import Track
from sim.sensors.base import utime

EPS_M = 1e-6
# A frame whose wavefront is a gap g short of us cannot arrive within
# g / (2 c): the sound speed along the path and the receiver's speed would
# have to double the closing rate. Frames are looked at again only then, so
# a frame in flight costs a few checks instead of one per physics step.
CLOSING_MARGIN = 2.0
EPS_S = 1e-9
# Reception intervals and own transmissions are kept this long after they
# end: long enough for a frame relayed late over an impaired link.
KEEP_S = 60.0


def overlaps(a: tuple[float, float], b: tuple[float, float]) -> bool:
    """Two intervals share more than an instant (back to back is no collision)."""
    return a[0] < b[1] - EPS_S and b[0] < a[1] - EPS_S


class Receiver:
    def __init__(self, cfg: ModemConfig, vehicle: str, seed: int, env: Environment, status: modem_status_t) -> None:
        self.cfg = cfg
        self.vehicle = vehicle
        self.seed = seed
        self.env = env
        self.status = status
        self.pending: list[acoustic_frame_t] = []
        self.foreign: list[acoustic_frame_t] = []  # for other vehicles: they only occupy the channel
        self._next_check: dict[int, float] = {}  # id(frame) -> sim time to look again
        self._heard: list[tuple[float, float, int]] = []  # (start, end, serial) of frames heard here
        self._serial = 0
        self.track = Track()  # where our vehicle was, step by step
        self._horizon = float("-inf")  # frames are judged up to this sim time
        self._sending: list[tuple[float, float]] = []  # our own transmissions
        self._doomed: dict[int, str] = {}  # id(frame in the water) -> "collided" / "deaf"
        self.bad_frames = 0  # from no valid vehicle id: dropped

    def hear(self, frame: acoustic_frame_t) -> None:
        """A frame entered the water somewhere: track it if it is meant for us."""
        if not VEHICLE_ID.fullmatch(frame.src_vehicle):
            self.bad_frames += 1
            return
        if frame.src_vehicle == self.vehicle:
            return  # a modem does not hear itself
        if frame.dst_vehicle and frame.dst_vehicle != self.vehicle:
            self.foreign.append(frame)  # addressed to another vehicle: heard, never delivered
            return
        self.pending.append(frame)

    def transmit(self, start: float, end: float) -> None:
        """Our modem sends over [start, end]: frames that will arrive meanwhile are lost."""
        self._sending.append((start, end))
        for f, iv in self._predicted():
            if overlaps(iv, (start, end)):
                self._doomed.setdefault(id(f), "deaf")

    def _position_at(self, t: float) -> tuple[float, float, float]:
        """Our position at the last step at or before t (the first one known if none)."""
        tr = self.track
        if not tr.times:
            return (0.0, 0.0, 0.0)
        return tr.positions[max(tr.last_at_or_before(t), 0)]

    def _arrival(self, f: acoustic_frame_t, horizon: float):
        """(arrival time, range) if f's wavefront reached us at a step up to the
        horizon, else None (and the time to look again is noted)."""
        tr, t0 = self.track, f.utime / 1e6
        tx_pos = (f.tx_north_m, f.tx_east_m, f.tx_depth_m)
        i = tr.first_at_or_after(max(self._next_check.get(id(f), t0), t0))
        while i < len(tr) and tr.times[i] <= horizon + 1e-9:
            t, position = tr.times[i], tr.positions[i]
            c = self.env.path_sound_speed(t0, tx_pos, position)
            d = distance_3d(tx_pos, position)
            gap = d - c * (t - t0)
            if gap <= EPS_M:
                self._next_check.pop(id(f), None)
                return t0 + d / c, d
            # cannot arrive before this: skip the steps in between
            self._next_check[id(f)] = t + gap / (CLOSING_MARGIN * c)
            i = max(i + 1, tr.first_at_or_after(self._next_check[id(f)]))
        return None

    def _arrivals(self, frames: list[acoustic_frame_t], horizon: float, arrived: list, mine: bool):
        """Move the frames whose wavefront reached us by the horizon to `arrived`; the rest stay."""
        waiting = []
        for f in frames:
            got = self._arrival(f, horizon) if f.utime / 1e6 <= horizon + 1e-9 else None
            if got is None:
                waiting.append(f)
            else:
                arrived.append((got[0], f, got[1], mine))
        return waiting

    def _predicted(self) -> list[tuple[acoustic_frame_t, tuple[float, float]]]:
        """Frames sent by the horizon and still in the water that will reach us,
        with their reception intervals predicted from our position at the horizon."""
        out = []
        h = self._horizon
        position = self._position_at(h)
        for f in self.pending + self.foreign:
            if f.utime / 1e6 > h + 1e-9:
                continue  # not judged yet: which of them are in is not certain
            tx_pos = (f.tx_north_m, f.tx_east_m, f.tx_depth_m)
            c = self.env.path_sound_speed(f.utime / 1e6, tx_pos, position)
            d = distance_3d(tx_pos, position)
            if d <= self.cfg.max_range_m:
                start = f.utime / 1e6 + d / c
                out.append((f, (start, start + f.duration_us / 1e6)))
        return out

    def _fate(self, f: acoustic_frame_t, iv: tuple[float, float], serial: int) -> str:
        """ "deaf", "collided" or "" for a frame heard over iv; frames in the
        water that it overlaps are marked to be lost too."""
        fate = self._doomed.pop(id(f), "")
        if iv[1] - iv[0] <= EPS_S:
            return fate  # no time on the air: overlaps nothing
        if any(overlaps(iv, s) for s in self._sending):
            fate = fate or "deaf"
        if any(key != serial and overlaps(iv, (a, b)) for a, b, key in self._heard):
            fate = fate or "collided"
        for other, piv in self._predicted():
            if overlaps(iv, piv):
                self._doomed.setdefault(id(other), "collided")
                fate = fate or "collided"
        return fate

    def record(self, t: float, position: tuple[float, float, float]) -> None:
        """Our true position after the physics step that ended at t."""
        self.track.add(t, position)

    def step(self, t: float, position: tuple[float, float, float]) -> list[modem_rx_t]:
        """Frames whose wavefront reached us by sim time t, lost ones left out."""
        self.record(t, position)
        return self.judge(t)

    def judge(self, horizon: float) -> list[modem_rx_t]:
        """Frames sent by the horizon whose wavefront reached us by then, lost ones
        left out (the horizon never goes back)."""
        h = self._horizon = max(self._horizon, horizon)
        arrived: list = []
        self.pending = self._arrivals(self.pending, h, arrived, True)
        self.foreign = self._arrivals(self.foreign, h, arrived, False)
        self._heard = [x for x in self._heard if x[1] > h - KEEP_S]
        self._sending = [s for s in self._sending if s[1] > h - KEEP_S]
        batch = []
        for t_arr, f, d, mine in sorted(arrived, key=lambda a: (a[0], a[1].src_vehicle, a[1].seq)):
            if d > self.cfg.max_range_m:
                self._doomed.pop(id(f), None)
                if mine:
                    self.status.out_of_range += 1
                continue  # too faint to hear, or to disturb another frame
            iv = (t_arr, t_arr + f.duration_us / 1e6)
            self._serial += 1
            if iv[1] - iv[0] > EPS_S:
                self._heard.append((iv[0], iv[1], self._serial))
            batch.append((iv, self._serial, t_arr, f, d, mine))
        # every frame of the batch is in _heard before any is judged, so two
        # that arrive in one step see each other
        fates = [self._fate(f, iv, serial) for iv, serial, _, f, _, _ in batch]
        out = []
        for (iv, _, t_arr, f, d, mine), fate in zip(batch, fates):
            if not mine:
                continue
            if fate == "deaf":
                self.status.deaf += 1
                continue
            if fate == "collided":
                self.status.collided += 1
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

"""Sidescan detections: one look per target per pass, decided by the lateral range curve.

A sidescan images a thin fan across the track, so a seabed object is looked
at once, when it passes abeam. Every `1 / update_hz` of sim time the model
puts each target in the vehicle's frame (along and across track); a target
whose along-track coordinate went from ahead to abeam-or-behind since the
last update is being looked at now, at ground range |across|. It is detected
with probability P(|across|, altitude) (sim.sonar.curve) and becomes a
sidescan_contact_t with the sonar's position error (along and across track)
plus the vehicle's navigation error when the simulated INS provides one.
A target is looked at most once per `relook_s` (a vehicle wobbling on its
line does not get extra looks).

Mine-likeness: each contact's `confidence` is a score drawn from the
configuration's confusion model (sonar.score): Beta(mine_a, mine_b) for a
mine-like object, Beta(clutter_a, clutter_b) for clutter and false alarms,
from a stream of its own so the score model does not move the detections;
`classification` is "mine_like" when the score reaches the threshold, else
"unknown" (a mine or a false alarm) or "clutter" (a clutter object).

Seabed false alarms: a Poisson process of `false_alarms_per_km2` over the
area imaged since the last update (the band [g, F) on each side, times the
distance run), each placed uniformly in that strip.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from auv import sidescan_contact_t
from sim.model import Truth
from sim.noise import Noise
from sim.periodic import Periodic
from sim.sensors.base import utime
from sim.sonar.config import SonarConfig
from sim.sonar.curve import LateralRangeCurve
from sim.sonar.targets import MINE_LIKE, TargetField

NavError = Callable[[], tuple[float, float]]


class Sidescan:
    def __init__(
        self, cfg: SonarConfig, field: TargetField, seed: int, vehicle: str, nav_error: NavError | None = None
    ) -> None:
        self.cfg = cfg
        self.field = field
        self.vehicle = vehicle
        self.curve = LateralRangeCurve(cfg)
        self.rng = Noise(f"{seed}:sonar")
        self.score_rng = Noise(f"{seed}:sonar_score")
        self.nav_error = nav_error
        ts = field.targets
        self._n = np.array([t.north_m for t in ts], dtype=float)
        self._e = np.array([t.east_m for t in ts], dtype=float)
        self._mine = np.array([t.kind == MINE_LIKE for t in ts], dtype=bool)
        self._factor = np.where(self._mine, 1.0, cfg.clutter_pd_factor)
        self._prev_along = np.full(len(ts), np.nan)
        self._last_look = np.full(len(ts), -np.inf)
        self.schedule = Periodic(1.0 / cfg.update_hz, skip_slack=1e-9)
        self._prev_pos: tuple[float, float] | None = None
        self.contacts = 0
        # per target: looks (passes abeam while imaging) and detections
        self.looks = np.zeros(len(ts), dtype=int)
        self.detections = np.zeros(len(ts), dtype=int)
        self.look_ranges: list[tuple[int, float, float, bool]] = []  # (index, y, altitude, detected)
        self.false_alarms = 0
        self.imaged_area_m2 = 0.0

    def next_due(self) -> float:
        return self.schedule.next_t

    def poll(self, tr: Truth) -> list:
        """The contacts of this update (maybe none); [] when no update is due."""
        t = tr.t
        if not self.schedule.due(t):
            return []
        self.schedule.advance(t)
        n0, e0, _, roll, pitch, psi = tr.eta
        h = tr.altitude_m
        g, far = self.curve.imaged_band(h)
        imaging = far > 0.0 and max(abs(roll), abs(pitch)) <= self.cfg.max_attitude_rad
        c, s = math.cos(psi), math.sin(psi)
        out = []
        if len(self._n):
            dn, de = self._n - n0, self._e - e0
            along = dn * c + de * s
            across = -dn * s + de * c
            crossed = (self._prev_along > 0.0) & (along <= 0.0)
            self._prev_along = along
            if imaging and crossed.any():
                for i in np.nonzero(crossed & (np.abs(across) < far))[0]:
                    if t - self._last_look[i] < self.cfg.relook_s:
                        continue
                    self._last_look[i] = t
                    y = float(across[i])
                    p = self.curve.pd(abs(y), h, float(self._factor[i]))
                    self.looks[i] += 1
                    hit = p > 0.0 and self.rng.random() < p
                    self.look_ranges.append((int(i), abs(y), h, hit))
                    if hit:
                        self.detections[i] += 1
                        out.append(self._target_contact(tr, int(i), y, p, c, s))
        if imaging and self._prev_pos is not None:
            out.extend(self._false_alarms(tr, g, far, c, s))
        self._prev_pos = (n0, e0) if imaging else None
        return out

    # ------------------------------------------------------------ contacts
    def _contact(
        self, tr: Truth, north: float, east: float, y: float, c: float, s: float, confidence: float, classification: str
    ):
        """A contact at ground range y (signed, + starboard) of a true point (north, east)."""
        cfg = self.cfg
        ea = self.rng.gauss(cfg.along_track_sigma_m)
        er = self.rng.gauss(cfg.range_sigma_m) * (1.0 if y >= 0.0 else -1.0)
        dn, de = self.nav_error() if self.nav_error is not None else (0.0, 0.0)
        self.contacts += 1
        m = sidescan_contact_t()
        m.utime, m.vehicle, m.contact_id = utime(tr.t), self.vehicle, self.contacts
        m.side = sidescan_contact_t.SIDE_STARBOARD if y >= 0.0 else sidescan_contact_t.SIDE_PORT
        m.ground_range_m = abs(y) + (er if y >= 0.0 else -er)
        m.vehicle_altitude_m = tr.altitude_m
        m.slant_range_m = math.hypot(m.ground_range_m, tr.altitude_m)
        m.north_m = north + ea * c - er * s + dn
        m.east_m = east + ea * s + er * c + de
        m.position_sigma_m = math.hypot(cfg.along_track_sigma_m, cfg.range_sigma_m)
        m.confidence = min(1.0, max(0.0, confidence))
        m.classification = classification
        return m

    def score(self, mine: bool) -> float:
        """A mine-likeness score from the confusion model."""
        m = self.cfg.score
        return self.score_rng.beta(m.mine_a, m.mine_b) if mine else self.score_rng.beta(m.clutter_a, m.clutter_b)

    def _target_contact(self, tr: Truth, i: int, y: float, p: float, c: float, s: float):
        mine = bool(self._mine[i])
        conf = self.score(mine)
        cls = MINE_LIKE if conf >= self.cfg.score.threshold else ("unknown" if mine else "clutter")
        return self._contact(tr, float(self._n[i]), float(self._e[i]), y, c, s, conf, cls)

    def _false_alarms(self, tr: Truth, g: float, far: float, c: float, s: float) -> list:
        n0, e0 = tr.eta[0], tr.eta[1]
        run = math.hypot(n0 - self._prev_pos[0], e0 - self._prev_pos[1])
        area = 2.0 * (far - g) * run
        self.imaged_area_m2 += area
        out = []
        for _ in range(self.rng.poisson(self.cfg.false_alarms_per_km2 * area / 1e6)):
            back = -self.rng.random() * run
            y = (g + self.rng.random() * (far - g)) * (1.0 if self.rng.random() < 0.5 else -1.0)
            north, east = n0 + back * c - y * s, e0 + back * s + y * c
            conf = self.score(False)
            cls = MINE_LIKE if conf >= self.cfg.score.threshold else "unknown"
            self.false_alarms += 1
            out.append(self._contact(tr, north, east, y, c, s, conf, cls))
        return out

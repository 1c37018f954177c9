"""Long-baseline acoustic ranging: two-way travel times to fixed transponders.

One interrogation at t0: the ping travels to each transponder, waits its
turnaround time and comes back to where the vehicle is by then. Travel time
is range / the mean sound speed along the straight path (Environment.
path_sound_speed: a linear profile's mean, or, in a world with an ocean, the
harmonic mean of TEOS-10's speeds along it), plus Gaussian timing noise, plus occasional long outliers (multipath: a reflected
path is always longer, never shorter). The message is published when the
last reply has arrived, stamped with t0, as a real receiver would.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from auv import lbl_ranges_t
from confcheck import setting
from sim.environment import Environment
from sim.model import Truth
from sim.ocean import Ocean
from sim.sensors.base import Sensor, SensorConfig, utime


@dataclass
class LblConfig(SensorConfig):
    rate_hz: float = setting(0.1, gt=0.0, unit="Hz")  # one interrogation every 10 s
    noise: float = setting(1.25, ge=0.0)  # range noise, 1-sigma [m] (converted to time)
    bias: float = 0.0  # range offset [m]
    outlier_probability: float = setting(0.05, ge=0.0, lt=1.0)
    outlier_max_m: float = setting(50.0, ge=0.0)  # outliers add U(0, this) metres of path
    max_range_m: float = setting(3000.0, ge=0.0)  # no reply beyond this
    assumed_sound_speed_mps: float = 0.0  # what the vehicle assumes; 0 = the world mean


class Lbl(Sensor):
    name = "lbl"
    topic = "LBL"
    config_class = LblConfig
    env_needs = ("sound_speed", "lbl")  # the travel times; the transponders
    uses = ("env",)
    cfg: LblConfig

    @classmethod
    def nav_config(cls, cfg: LblConfig, env) -> list[str]:
        p = env
        lines = [f"lbl_range_noise_m {max(math.hypot(cfg.noise, cfg.bias), 0.01):.6g}"]
        if cfg.assumed_sound_speed_mps > 0:
            lines.append(f"sound_speed_mps {cfg.assumed_sound_speed_mps:.9g}")
        elif p.ocean is not None:
            # the vehicle's profile: a straight line through a cast at the origin before the run
            deepest = max([t.depth_m for t in p.transponders] + [50.0])
            ocean = Ocean(p.ocean, p.seed, p.origin_latitude_deg, p.origin_longitude_deg)
            c0, gradient = ocean.profile_fit(deepest)
            lines += [f"sound_speed_mps {c0:.9g}", f"sound_speed_gradient_per_m {gradient:.9g}"]
        else:
            lines += [
                f"sound_speed_mps {p.sound_speed_mps:.9g}",
                f"sound_speed_gradient_per_m {p.sound_speed_gradient_per_m:.9g}",
            ]
        lines.append("# transponder ID NORTH_M EAST_M DEPTH_M TURNAROUND_S")
        for t in p.transponders:
            lines.append(f"transponder {t.id} {t.north_m:.9g} {t.east_m:.9g} {t.depth_m:.9g} {t.turnaround_s:.9g}")
        return lines

    def __init__(self, cfg, seed, vehicle, env: Environment) -> None:
        super().__init__(cfg, seed, vehicle)
        self.env = env
        self.pending: list[tuple[float, object]] = []  # (publish time, message)
        self.outliers = 0

    def poll(self, tr: Truth):
        # a pending interrogation comes out when its last reply is in
        out = None
        if self.pending and tr.t >= self.pending[0][0] - 1e-9:
            out = self.pending.pop(0)[1]
        msg = super().poll(tr)
        if msg is not None:
            self.pending.append(msg)
        return out

    def poll_encoded(self, tr: Truth) -> bytes | None:
        msg = self.poll(tr)  # published later than measured: through poll()
        return None if msg is None else self.encode(msg)

    def next_due(self) -> float:
        due = super().next_due()
        return min(due, self.pending[0][0]) if self.pending else due

    def measure(self, tr: Truth):
        c = self.cfg
        env = self.env
        n0, e0, d0 = tr.eta[0], tr.eta[1], tr.eta[2]
        vn, ve, vd = tr.velocity_ned()
        ids, twtt, turn = [], [], []
        for x in env.params.transponders:
            dist = math.sqrt((x.north_m - n0) ** 2 + (x.east_m - e0) ** 2 + (x.depth_m - d0) ** 2)
            if dist > c.max_range_m:
                continue
            cs = env.path_sound_speed(tr.t, (n0, e0, d0), (x.north_m, x.east_m, x.depth_m))
            t_out = dist / cs
            # where the vehicle is when the reply arrives: constant velocity
            # over the few seconds, solved by two fixed-point passes
            t_back = t_out
            for _ in range(2):
                dt = t_out + x.turnaround_s + t_back
                n1, e1, d1 = n0 + vn * dt, e0 + ve * dt, d0 + vd * dt
                back = math.sqrt((x.north_m - n1) ** 2 + (x.east_m - e1) ** 2 + (x.depth_m - d1) ** 2)
                t_back = back / env.path_sound_speed(tr.t, (n1, e1, d1), (x.north_m, x.east_m, x.depth_m))
            extra_m = c.bias + self.gauss(c.noise)
            if c.outlier_probability > 0.0 and self.rng.random() < c.outlier_probability:
                extra_m += self.rng.uniform(0.0, c.outlier_max_m)
                self.outliers += 1
            ids.append(x.id)
            # the noise is on the two-way path, expressed as metres of range
            twtt.append(t_out + t_back + x.turnaround_s + 2.0 * extra_m / cs)
            turn.append(x.turnaround_s)
        m = lbl_ranges_t()
        m.utime, m.vehicle = utime(tr.t), self.vehicle
        m.sound_speed_mps = c.assumed_sound_speed_mps or env.sound_speed(d0, tr.t, n0, e0)
        m.n_replies = len(ids)
        m.transponder_id, m.two_way_travel_s, m.turnaround_s = ids, twtt, turn
        publish_at = tr.t + max(twtt, default=0.0)
        return (publish_at, m)

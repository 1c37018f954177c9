"""The world's environment: currents, waves, bathymetry, sound speed, LBL, the ocean.

Everything here is a deterministic function of (time, position, seed), built
from exactly the parameters that auv.env_model_t carries. Why: any simulator
can serve the environment, and a client that takes over the server role after
a failover continues it from the same parameters without a jump, because no
hidden state (no integrated random walk) is involved.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from pathlib import Path

from confcheck import setting
from sim.bathymetry import Bathymetry
from sim.ocean import (
    UNIFORM_SALINITY_PSU,
    UNIFORM_TEMPERATURE_C,
    Front,
    Ocean,
    OceanParams,
    Plume,
    Thermocline,
    WaterMass,
)

# What of the world a vehicle may ask a multi-HIL world for (multihil.needs,
# env_needs_t), and what a sensor declares it reads (Sensor.env_needs).
ENV_VARIABLES = ("current", "waves", "bathymetry", "sound_speed", "lbl", "ocean")
G = 9.81
RHO_SEAWATER = 1025.0  # kg/m^3, the depth sensor's conversion too
# Spatial wavelength of the slow current variation [m]: large against a
# vehicle's range, so the variation reads as "the tide turning".
CURRENT_VARIATION_WAVELENGTH_M = 10_000.0
WAVE_COMPONENTS = (0.8, 0.9, 1.0, 1.15, 1.3, 1.5)  # frequencies / peak frequency


@dataclass
class CurrentLayer:
    depth_m: float
    north_mps: float
    east_mps: float
    down_mps: float = 0.0


@dataclass
class Transponder:
    id: int
    north_m: float
    east_m: float
    depth_m: float
    turnaround_s: float = setting(0.0, ge=0.0)


@dataclass
class EnvParams:
    world: str = "default"
    seed: int = 1
    origin_latitude_deg: float = 41.52
    origin_longitude_deg: float = -70.67
    current: list[CurrentLayer] = field(default_factory=list)
    current_variation_mps: float = 0.0
    current_variation_period_s: float = setting(43200.0, ge=0.0)
    wave_height_m: float = setting(0.0, ge=0.0)
    wave_period_s: float = setting(8.0, ge=0.0)
    wave_direction_rad: float = 0.0
    bathymetry_ref: str = "flat:depth=50"
    sound_speed_mps: float = setting(1500.0, gt=0.0)
    sound_speed_gradient_per_m: float = 0.0
    transponders: list[Transponder] = field(default_factory=list)
    # temperature and salinity (sim.ocean, docs/sampling.md); None: uniform water
    # and the constant sound speed above
    ocean: OceanParams | None = None


def _pm_weight(ratio: float) -> float:
    """Pierson-Moskowitz spectral shape at omega/omega_peak (peak = 1)."""
    return ratio**-5 * math.exp(-1.25 * ratio**-4)


class Environment:
    def __init__(self, params: EnvParams, base_dir: Path | None = None) -> None:
        self.params = params
        p = params
        layers = sorted(p.current, key=lambda c: c.depth_m)
        self._layers = [(c.depth_m, c.north_mps, c.east_mps, c.down_mps) for c in layers]
        self.bathymetry = Bathymetry(p.bathymetry_ref, base_dir)
        # seeded, fixed phases: the same seed gives the same sea everywhere
        rng = random.Random(f"{p.seed}:env")
        self._var_phase = rng.uniform(0.0, 2.0 * math.pi)
        self._var_dir = rng.uniform(0.0, 2.0 * math.pi)
        self._waves: list[tuple[float, float, float, float]] = []
        if p.wave_height_m > 0.0 and p.wave_period_s > 0.0:
            wp = 2.0 * math.pi / p.wave_period_s
            weights = [_pm_weight(r) for r in WAVE_COMPONENTS]
            total = sum(weights)
            # sum a_i^2 = Hs^2 / 8, so 4 sqrt(m0) = Hs
            for r, wgt in zip(WAVE_COMPONENTS, weights):
                a = math.sqrt(p.wave_height_m**2 / 8.0 * wgt / total)
                w = wp * r
                self._waves.append((a, w, w * w / G, rng.uniform(0.0, 2.0 * math.pi)))
        self._wave_cos = math.cos(p.wave_direction_rad)
        self._wave_sin = math.sin(p.wave_direction_rad)
        # what current() needs per call, computed once (it runs every physics step)
        self._layer_pairs = list(zip(self._layers, self._layers[1:]))
        self._varies = p.current_variation_mps != 0.0 and p.current_variation_period_s > 0.0
        self._var_cos, self._var_sin = math.cos(self._var_dir), math.sin(self._var_dir)
        # per wave component: a w (orbital speed amplitude at the surface), -k, k, w, phase
        self._orbital = [(a * w, -k, k, w, ph) for a, w, k, ph in self._waves]
        self.ocean: Ocean | None = None
        if p.ocean is not None:
            self.ocean = Ocean(
                p.ocean, p.seed, p.origin_latitude_deg, p.origin_longitude_deg, self.current_displacement, base_dir
            )

    def replace_with(self, other: "Environment") -> None:
        """Become other's world, in place: every part that holds this object (the
        model, the sensors, the modem, the multi-HIL node) sees the new one from
        its next call, with no reference to hand round."""
        self.__dict__.update(other.__dict__)

    def set_regular_wave(self, height_m: float, period_s: float, phase: float = 0.0) -> None:
        """Replace the spectrum with one regular wave (checks against linear theory)."""
        w = 2.0 * math.pi / period_s
        k = w * w / G
        self._waves = [(height_m / 2.0, w, k, phase)]
        self._orbital = [(height_m / 2.0 * w, -k, k, w, phase)]

    @property
    def has_waves(self) -> bool:
        return bool(self._waves)

    # ------------------------------------------------------------- currents
    def current_profile(self, depth: float) -> tuple[float, float, float]:
        ls = self._layers
        if not ls:
            return 0.0, 0.0, 0.0
        if depth <= ls[0][0]:
            return ls[0][1], ls[0][2], ls[0][3]
        for (d0, n0, e0, w0), (d1, n1, e1, w1) in self._layer_pairs:
            if depth <= d1:
                f = (depth - d0) / (d1 - d0) if d1 > d0 else 1.0
                return n0 + f * (n1 - n0), e0 + f * (e1 - e0), w0 + f * (w1 - w0)
        return ls[-1][1], ls[-1][2], ls[-1][3]

    def current(self, t: float, north: float, east: float, depth: float) -> tuple[float, float, float]:
        """Water velocity (NED) from the profile, the slow variation and the waves."""
        return self.water(t, north, east, depth)[0]

    def water(
        self, t: float, north: float, east: float, depth: float
    ) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """The water's velocity and acceleration (NED) at a point, in one call
        (the simulator's hot path). Only the waves accelerate it: the tide's
        variation is hours slow."""
        cn, ce, cd = self.current_profile(depth)
        if self._varies:
            p = self.params
            vc, vs = self._var_cos, self._var_sin
            s = north * vc + east * vs
            amp = p.current_variation_mps * math.sin(
                2.0 * math.pi * (t / p.current_variation_period_s + s / CURRENT_VARIATION_WAVELENGTH_M)
                + self._var_phase
            )
            cn += amp * vc
            ce += amp * vs
        if self._orbital:
            wh, wv, ah, av = self.wave_kinematics(t, north, east, depth)
            wc, ws = self._wave_cos, self._wave_sin
            return (cn + wh * wc, ce + wh * ws, cd + wv), (ah * wc, ah * ws, av)
        return (cn, ce, cd), (0.0, 0.0, 0.0)

    def current_displacement(
        self, depth: float, north: float, east: float, t0: float, t1: float
    ) -> tuple[float, float]:
        """How far the water at a depth moves horizontally over [t0, t1] [m]: the
        profile's current, plus the slow variation integrated in closed form with
        its phase held at (north, east) (its wavelength, 10 km, is long against
        the distance water moves in hours); the waves' orbits close on themselves
        (no Stokes drift). What carries the ocean's plumes."""
        cn, ce, _ = self.current_profile(depth)
        dt = t1 - t0
        dn, de = cn * dt, ce * dt
        if self._varies:
            p = self.params
            w = 2.0 * math.pi / p.current_variation_period_s
            s = north * self._var_cos + east * self._var_sin
            ph = 2.0 * math.pi * s / CURRENT_VARIATION_WAVELENGTH_M + self._var_phase
            disp = p.current_variation_mps / w * (math.cos(w * t0 + ph) - math.cos(w * t1 + ph))
            dn += disp * self._var_cos
            de += disp * self._var_sin
        return dn, de

    # ---------------------------------------------------------------- waves
    def wave_orbital(self, t: float, north: float, east: float, depth: float) -> tuple[float, float]:
        """Deep-water orbital velocity: along the wave direction, and down [m/s]
        (the velocity part of wave_kinematics; the world's samples use it)."""
        uh, uv, _, _ = self.wave_kinematics(t, north, east, depth)
        return uh, uv

    def wave_kinematics(self, t: float, north: float, east: float, depth: float) -> tuple[float, float, float, float]:
        """Deep-water (Airy) velocity and acceleration of the water: along the
        wave direction and down [m/s, m/s^2]. Per component of amplitude a,
        frequency w, wavenumber k = w^2/g, phase th = k s - w t + ph:
        u = a w e^-kz cos th, w_down = -a w e^-kz sin th. The acceleration is
        the particles' own, Du/Dt = du/dt + (u . grad) u: with the local
        derivative alone, a body that follows the water (Froude-Krylov plus
        added mass) would drift down through the wave field."""
        s = north * self._wave_cos + east * self._wave_sin
        d = max(depth, 0.0)
        uh = uv = ah = av = 0.0
        gc = gs = 0.0  # sums of a w k e^-kz cos th and of ... sin th
        exp, cos, sin = math.exp, math.cos, math.sin
        for aw, nk, k, w, ph in self._orbital:
            decay = exp(nk * d)
            if decay < 1e-4:
                continue
            th = k * s - w * t + ph
            c, sn = cos(th), sin(th)
            v = aw * decay
            uh += v * c
            uv -= v * sn
            ah += v * w * sn
            av += v * w * c
            gc += v * k * c
            gs += v * k * sn
        # grad: d(uh)/ds = -gs, d(uh)/dz = -gc, d(uv)/ds = -gc, d(uv)/dz = gs
        return uh, uv, ah - uh * gs - uv * gc, av - uh * gc + uv * gs

    def wave_pressure(self, t: float, north: float, east: float, depth: float) -> float:
        """Dynamic pressure of the waves at a depth [Pa], linear theory:
        rho g sum a e^-kz cos th (in phase with the surface above)."""
        s = north * self._wave_cos + east * self._wave_sin
        d = max(depth, 0.0)
        return (
            RHO_SEAWATER * G * sum(a * math.exp(-k * d) * math.cos(k * s - w * t + ph) for a, w, k, ph in self._waves)
        )

    def wave_elevation(self, t: float, north: float, east: float) -> float:
        """Sea-surface elevation, positive up [m]."""
        s = north * self._wave_cos + east * self._wave_sin
        return sum(a * math.cos(k * s - w * t + ph) for a, w, k, ph in self._waves)

    # ------------------------------------------------------ seabed and sound
    def water_depth(self, north: float, east: float) -> float:
        return self.bathymetry.depth(north, east)

    def sound_speed(self, depth: float, t: float = 0.0, north: float = 0.0, east: float = 0.0) -> float:
        """Sound speed at a point [m/s]: TEOS-10's of the ocean's water there, or,
        in a world without `ocean:`, the constant plus the gradient times depth."""
        if self.ocean is not None:
            return self.ocean.sound_speed(t, north, east, depth)
        p = self.params
        return p.sound_speed_mps + p.sound_speed_gradient_per_m * depth

    def mean_sound_speed(self, depth_a: float, depth_b: float) -> float:
        """Mean speed along a straight path between two depths (linear profile;
        with an ocean: along the vertical at the origin at time 0)."""
        if self.ocean is not None:
            return self.ocean.path_sound_speed(0.0, (0.0, 0.0, depth_a), (0.0, 0.0, depth_b))
        return self.sound_speed(0.5 * (depth_a + depth_b))

    def path_sound_speed(self, t: float, a: tuple[float, float, float], b: tuple[float, float, float]) -> float:
        """The speed that gives the travel time of sound from a to b (north, east,
        depth) at time t: with an ocean, the harmonic mean of the local speeds
        along the straight path (sim.ocean.Ocean.path_sound_speed); without, the
        linear profile's mean between the two depths, as always."""
        if self.ocean is not None:
            return self.ocean.path_sound_speed(t, a, b)
        return self.mean_sound_speed(a[2], b[2])

    def temperature_salinity(self, t: float, north: float, east: float, depth: float) -> tuple[float, float]:
        """In-situ temperature [degC] and practical salinity [PSU] of the water at a
        point (uniform 12 degC, 35 PSU in a world without `ocean:`)."""
        if self.ocean is not None:
            return self.ocean.temperature_salinity(t, north, east, depth)
        return UNIFORM_TEMPERATURE_C, UNIFORM_SALINITY_PSU

    # ------------------------------------------------------ env_model_t I/O
    def to_env_model(self, utime: int, server_id: str = "", term: int = 0):
        from auv import current_layer_t, env_model_t, lbl_transponder_t

        p = self.params
        m = env_model_t()
        m.utime, m.server_id, m.term, m.world, m.seed = utime, server_id, term, p.world, p.seed
        m.origin_latitude_deg, m.origin_longitude_deg = p.origin_latitude_deg, p.origin_longitude_deg
        m.current = []
        for c in p.current:
            layer = current_layer_t()
            layer.depth_m, layer.north_mps, layer.east_mps, layer.down_mps = (
                c.depth_m,
                c.north_mps,
                c.east_mps,
                c.down_mps,
            )
            m.current.append(layer)
        m.n_current_layers = len(m.current)
        m.current_variation_mps = p.current_variation_mps
        m.current_variation_period_s = p.current_variation_period_s
        m.wave_height_m, m.wave_period_s, m.wave_direction_rad = (
            p.wave_height_m,
            p.wave_period_s,
            p.wave_direction_rad,
        )
        m.bathymetry_ref, m.bathymetry_sha256 = p.bathymetry_ref, self.bathymetry.sha256
        m.sound_speed_mps, m.sound_speed_gradient_per_m = (p.sound_speed_mps, p.sound_speed_gradient_per_m)
        m.transponders = []
        for tr in p.transponders:
            x = lbl_transponder_t()
            x.id, x.north_m, x.east_m, x.depth_m, x.turnaround_s = (
                tr.id,
                tr.north_m,
                tr.east_m,
                tr.depth_m,
                tr.turnaround_s,
            )
            m.transponders.append(x)
        m.n_transponders = len(m.transponders)
        self._ocean_to_env_model(m)
        return m

    def _ocean_to_env_model(self, m) -> None:
        from auv import ocean_plume_t

        o = self.params.ocean
        m.ocean = o is not None
        m.plumes = []
        if o is None:
            m.n_plumes = 0
            return
        m.ocean_grid_ref, m.ocean_grid_start = o.grid, o.grid_start
        m.ocean_grid_sha256 = self.ocean.grid.sha256 if self.ocean is not None and self.ocean.grid is not None else ""
        f = o.front
        m.front_offset_m, m.front_angle_rad, m.front_amplitude_m = f.offset_m, f.angle_rad, f.amplitude_m
        m.front_wavelength_m, m.front_period_s, m.front_width_m = f.wavelength_m, f.period_s, f.width_m
        m.front_drift_mps = f.drift_mps
        m.water_a_temperature_c, m.water_a_salinity_psu = o.water_a.temperature_c, o.water_a.salinity_psu
        m.water_b_temperature_c, m.water_b_salinity_psu = o.water_b.temperature_c, o.water_b.salinity_psu
        m.deep_temperature_c, m.deep_salinity_psu = o.deep.temperature_c, o.deep.salinity_psu
        m.thermocline_depth_m, m.thermocline_thickness_m = o.thermocline.depth_m, o.thermocline.thickness_m
        for pl in o.plumes:
            x = ocean_plume_t()
            x.north_m, x.east_m, x.depth_m, x.start_s = pl.north_m, pl.east_m, pl.depth_m, pl.start_s
            x.radius_m, x.thickness_m, x.diffusivity_m2ps = pl.radius_m, pl.thickness_m, pl.diffusivity_m2ps
            x.temperature_c, x.salinity_psu = pl.temperature_c, pl.salinity_psu
            m.plumes.append(x)
        m.n_plumes = len(m.plumes)

    @staticmethod
    def _ocean_from_env_model(m) -> OceanParams | None:
        if not m.ocean:
            return None
        return OceanParams(
            front=Front(
                m.front_offset_m,
                m.front_angle_rad,
                m.front_amplitude_m,
                m.front_wavelength_m,
                m.front_period_s,
                m.front_width_m,
                m.front_drift_mps,
            ),
            water_a=WaterMass(m.water_a_temperature_c, m.water_a_salinity_psu),
            water_b=WaterMass(m.water_b_temperature_c, m.water_b_salinity_psu),
            deep=WaterMass(m.deep_temperature_c, m.deep_salinity_psu),
            thermocline=Thermocline(m.thermocline_depth_m, m.thermocline_thickness_m),
            plumes=[
                Plume(
                    x.north_m,
                    x.east_m,
                    x.depth_m,
                    x.start_s,
                    x.radius_m,
                    x.thickness_m,
                    x.diffusivity_m2ps,
                    x.temperature_c,
                    x.salinity_psu,
                )
                for x in m.plumes
            ],
            grid=m.ocean_grid_ref,
            grid_start=m.ocean_grid_start,
        )

    @staticmethod
    def params_from_env_model(m) -> EnvParams:
        return EnvParams(
            world=m.world,
            seed=m.seed,
            origin_latitude_deg=m.origin_latitude_deg,
            origin_longitude_deg=m.origin_longitude_deg,
            current=[CurrentLayer(c.depth_m, c.north_mps, c.east_mps, c.down_mps) for c in m.current],
            current_variation_mps=m.current_variation_mps,
            current_variation_period_s=m.current_variation_period_s,
            wave_height_m=m.wave_height_m,
            wave_period_s=m.wave_period_s,
            wave_direction_rad=m.wave_direction_rad,
            bathymetry_ref=m.bathymetry_ref,
            sound_speed_mps=m.sound_speed_mps,
            sound_speed_gradient_per_m=m.sound_speed_gradient_per_m,
            transponders=[Transponder(t.id, t.north_m, t.east_m, t.depth_m, t.turnaround_s) for t in m.transponders],
            ocean=Environment._ocean_from_env_model(m),
        )

"""What the environment server does for the world, beyond answering clocks:
serve each client the environment values it asked for, and step global time
in lockstep mode."""

from __future__ import annotations

import time

from auv import env_needs_t, env_sample_t
from sim.environment import Environment
from sim.multihil.lockstep import LockstepTracker

VARIABLE_BITS = {
    "current": env_sample_t.HAS_CURRENT,
    "waves": env_sample_t.HAS_WAVES,
    "bathymetry": env_sample_t.HAS_BATHYMETRY,
    "sound_speed": env_sample_t.HAS_SOUND_SPEED,
    "ocean": env_sample_t.HAS_OCEAN,
}


def evaluate(env: Environment, needs: env_needs_t, term: int) -> env_sample_t:
    """The variables a client asked for, at its position and time; only those are valid.

    Evaluated at the time the client stamped its request, so the answer does
    not depend on when the server got round to it.
    """
    s = env_sample_t()
    s.utime, s.client_id, s.vehicle, s.term = needs.utime, needs.client_id, needs.vehicle, term
    n, e, d = needs.north_m, needs.east_m, needs.depth_m
    t = needs.utime / 1e6
    s.north_m, s.east_m, s.depth_m = n, e, d
    s.current_ned_mps = [0.0, 0.0, 0.0]
    s.wave_orbital_ned_mps = [0.0, 0.0, 0.0]
    s.wave_elevation_m = s.water_depth_m = s.sound_speed_mps = 0.0
    s.temperature_c = s.salinity_psu = 0.0
    mask = 0
    for var in needs.variables:
        mask |= VARIABLE_BITS.get(var, 0)
    if mask & env_sample_t.HAS_CURRENT:
        s.current_ned_mps = list(env.current(t, n, e, d))
    if mask & env_sample_t.HAS_WAVES:
        wh, wv = env.wave_orbital(t, n, e, d)
        c, si = env._wave_cos, env._wave_sin
        s.wave_orbital_ned_mps = [wh * c, wh * si, wv]
        s.wave_elevation_m = env.wave_elevation(t, n, e)
    if mask & env_sample_t.HAS_BATHYMETRY:
        s.water_depth_m = env.water_depth(n, e)
    if mask & env_sample_t.HAS_SOUND_SPEED:
        s.sound_speed_mps = env.sound_speed(d, t, n, e)
    if mask & env_sample_t.HAS_OCEAN:
        s.temperature_c, s.salinity_psu = env.temperature_salinity(t, n, e, d)
    s.valid_mask = mask
    return s


class LockstepServer:
    """Steps global time: step n + 1 only once every participant reported n.

    Step 0 waits for `expect` participants (and for every name in
    `expect_names`, if given). A step is published again when a participant
    that owes it repeats its report of the step before (it lost the clock)."""

    def __init__(
        self, tracker: LockstepTracker, step_us: int, expect: int, log=print, expect_names: set[str] | None = None
    ) -> None:
        self.tracker = tracker
        self.step_us = step_us
        self.expect = expect
        self.expect_names = set(expect_names or ())
        self.republished = 0
        self.log = log
        self.started = False
        self.step = 0
        self.base_step = 0
        self.base_utime = 0
        self.published_at = 0.0

    def utime(self, step: int) -> int:
        return self.base_utime + (step - self.base_step) * self.step_us

    def resume(self, step: int, utime: int) -> None:
        """Continue a world already stepping: repeat its last step, then go on."""
        self.started = True
        self.step = self.base_step = step
        self.base_utime = utime
        self.published_at = time.monotonic()

    def ready(self) -> bool:
        """Step 0 may go: every participant it waits for has registered."""
        return len(self.tracker.parts) >= max(1, self.expect) and self.expect_names <= self.tracker.parts.keys()

    def poll(self) -> int | None:
        """The step to publish now, if any (a repeat of the current one after a loss)."""
        if not self.started:
            if self.ready():
                self.started = True
                self.published_at = time.monotonic()
                return self.step
            return None
        if self.tracker.owes(self.step):
            if self.tracker.missed_clock(self.step, self.published_at):
                self.published_at = time.monotonic()
                self.republished += 1
                return self.step
            self.tracker.drop_silent(self.step, self.published_at)
            if self.tracker.owes(self.step) or not self.tracker.parts:
                return None
        if not self.tracker.parts:
            return None
        self.step += 1
        self.published_at = time.monotonic()
        return self.step

"""Step-response figures from closed-loop samples (tests/plugins/pilot_world.py)."""

from __future__ import annotations

import math
from dataclasses import dataclass


def wrap_pi(a: float) -> float:
    return (a + math.pi) % (2 * math.pi) - math.pi


@dataclass
class Step:
    """How a variable answered a step of its setpoint at t0, seen until t1."""

    settle_s: float  # from t0 until it last left the tolerance band (t1 - t0: never settled)
    overshoot: float  # furthest past the target in the step's direction (>= 0)
    final_rms: float  # RMS error over the last `tail_s`
    final_p2p: float  # peak-to-peak error over the last `tail_s`: sustained oscillation
    mean_error: float  # mean error over the last `tail_s`

    def text(self, unit: str, scale: float = 1.0) -> str:
        return (
            f"settles in {self.settle_s:5.1f} s, overshoot {self.overshoot * scale:5.2f} {unit}, "
            f"then rms {self.final_rms * scale:5.2f} {unit}, p2p {self.final_p2p * scale:5.2f} {unit}, "
            f"mean {self.mean_error * scale:+5.2f} {unit}"
        )


def step_response(
    samples,
    key: str,
    t0: float,
    t1: float,
    start: float,
    target: float,
    tol: float,
    tail_s: float = 15.0,
    angle: bool = False,
) -> Step:
    seg = [s for s in samples if t0 <= s.t <= t1]
    assert seg, f"no samples between {t0} and {t1} s"
    diff = wrap_pi if angle else (lambda x: x)
    err = [diff(getattr(s, key) - target) for s in seg]
    direction = math.copysign(1.0, diff(target - start))
    last_out = t0
    for s, e in zip(seg, err):
        if abs(e) > tol:
            last_out = s.t
    tail = [e for s, e in zip(seg, err) if s.t >= t1 - tail_s]
    return Step(
        settle_s=last_out - t0,
        overshoot=max(0.0, max(direction * e for e in err)),
        final_rms=math.sqrt(sum(e * e for e in tail) / len(tail)),
        final_p2p=max(tail) - min(tail),
        mean_error=sum(tail) / len(tail),
    )


def mean_abs(samples, key: str, t0: float, t1: float, target: float) -> tuple[float, float]:
    """Mean and largest |value - target| over [t0, t1]."""
    errs = [abs(getattr(s, key) - target) for s in samples if t0 <= s.t <= t1]
    return sum(errs) / len(errs), max(errs)

"""NTP-style estimate of the global clock from request/response timestamps.

Each exchange gives t1 (client send, local), t2 (server receive, global),
t3 (server send, global), t4 (client receive, local). With the client's local
time scaled by the warp, offset = ((t2 - t1) + (t3 - t4)) / 2 and
delay = (t4 - t1) - (t3 - t2). Queueing anywhere on the path (a busy server,
a jittery link) adds to the delay and, unevenly, to one direction: so only
the samples of least delay in the window are trusted (delay filtering): the least-delay sample of each `bin_s` of local
time, and a line through the last of those gives both the offset now and
the drift of the local clock (an old sample alone would be stale by the
drift accumulated since).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass


@dataclass
class Sample:
    local_mid_us: float  # local time halfway through the exchange
    offset_us: float  # global - warp * local at that time
    delay_us: float  # round trip less the server's turnaround


class SyncEstimator:
    DELAY_FLOOR_US = 30.0  # delay excess below this counts as equally good

    def __init__(self, warp: float = 1.0, window: int = 250, bin_s: float = 1.0, bins: int = 20) -> None:
        self.warp = warp
        self.samples: deque[Sample] = deque(maxlen=window)
        self.bin_us = bin_s * 1e6
        self.bins = bins
        self.offset_c = 0.0  # fitted offset at local_ref
        self.local_ref = 0.0
        self.drift = 0.0  # d offset / d local (global us per local us, beyond warp)
        self.best_delay_us = 0.0
        self.rejected = 0

    def add(self, t1: float, t2: float, t3: float, t4: float) -> Sample | None:
        """Add one exchange (t1, t4 local us; t2, t3 global us); None if impossible."""
        w = self.warp
        delay = (t4 - t1) * w - (t3 - t2)
        if t4 < t1 or t3 < t2 or delay < -1.0:
            self.rejected += 1
            return None
        s = Sample(0.5 * (t1 + t4), 0.5 * ((t2 - w * t1) + (t3 - w * t4)), max(delay, 0.0))
        self.samples.append(s)
        self._fit()
        return s

    def reset(self) -> None:
        """Forget every sample (a new server defines a new timeline)."""
        self.samples.clear()
        self.drift = 0.0

    @property
    def count(self) -> int:
        return len(self.samples)

    def good(self) -> list[Sample]:
        """The least-delay sample of each of the latest bins: what the estimate rests on."""
        best: dict[int, Sample] = {}
        for s in self.samples:
            k = int(s.local_mid_us // self.bin_us)
            if k not in best or s.delay_us < best[k].delay_us:
                best[k] = s
        return [best[k] for k in sorted(best)[-self.bins :]]

    def _fit(self) -> None:
        good = self.good()
        dmin = min(s.delay_us for s in good)
        self.best_delay_us = dmin
        if len(good) >= 3:
            xs = [s.local_mid_us for s in good]
            if max(xs) - min(xs) >= 1.5 * self.bin_us:  # drift needs a baseline
                # A sample's offset error is at most half its delay beyond the true
                # minimum: weigh by that bound, so a late partial bin cannot tilt the line;
                # excesses below the bins' typical one count alike (a jittery link).
                excess = sorted(s.delay_us - dmin for s in good)
                floor = max(self.DELAY_FLOOR_US, excess[len(excess) // 2])
                ws = [1.0 / (s.delay_us - dmin + floor) ** 2 for s in good]
                sw = sum(ws)
                mx = sum(w * x for w, x in zip(ws, xs)) / sw
                my = sum(w * s.offset_us for w, s in zip(ws, good)) / sw
                sxx = sum(w * (x - mx) ** 2 for w, x in zip(ws, xs))
                sxy = sum(w * (x - mx) * (s.offset_us - my) for w, x, s in zip(ws, xs, good))
                if sxx > 0.0:
                    self.drift = sxy / sxx
                    self.local_ref, self.offset_c = mx, my
                    return
        # too few bins or too short a baseline: the best recent sample, drift as before
        best = min(good[-2:], key=lambda s: s.delay_us)
        self.local_ref, self.offset_c = best.local_mid_us, best.offset_us

    def offset_at(self, local_us: float) -> float:
        """Estimated global - warp * local at a local time [us]."""
        return self.offset_c + self.drift * (local_us - self.local_ref)

    def global_at(self, local_us: float) -> float:
        return self.warp * local_us + self.offset_at(local_us)

    @property
    def drift_ppm(self) -> float:
        return self.drift / self.warp * 1e6

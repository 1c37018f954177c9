"""Clock probes: what `auv-multihil node --probe FILE` writes, and
how two of them compare. Every process on one machine reads the same
monotonic clock, so the client's global estimate and the server's global
time can be put side by side at the same instant."""

from __future__ import annotations

import bisect
from pathlib import Path


def load_probe(path: Path) -> list[tuple[float, float, str]]:
    """(monotonic us, global us, role) per line."""
    rows = []
    for line in Path(path).read_text().splitlines():
        mono, glob, role, _term = line.split()
        rows.append((float(mono), float(glob), role))
    return rows


def probe_errors(server: list, client: list, after_us: float = 0.0) -> list[float]:
    """Client's global estimate minus the server's global time at the same instant [us],
    interpolated between the server's probes (20 ms apart; gaps over 100 ms skipped)."""
    srv = [r for r in server if r[2] == "server"]
    ts = [r[0] for r in srv]
    out = []
    for mono, g, _ in client:
        if mono < after_us:
            continue
        k = bisect.bisect_left(ts, mono)
        if 0 < k < len(srv) and srv[k][0] - srv[k - 1][0] < 1e5:
            a, b = srv[k - 1], srv[k]
            out.append(g - (a[1] + (b[1] - a[1]) * (mono - a[0]) / (b[0] - a[0])))
    return out


def percentile(values: list[float], q: float) -> float:
    s = sorted(values)
    return s[min(len(s) - 1, int(q * len(s)))]

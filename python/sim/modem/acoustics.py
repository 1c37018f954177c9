"""The acoustic channel between two modems: pure functions, no state.

Frame loss follows a documented range curve (docs/modem.md):

    p_loss(r) = loss_at_zero + (loss_at_max_range - loss_at_zero) * (r / max_range_m) ** loss_exponent

for 0 <= r <= max_range_m, and every frame is lost beyond max_range_m. Whether
one frame is lost is decided by a uniform number drawn from a hash of the
seed, the sender, the frame's sequence number and send time, and the
receiver: the same scenario gives the same losses on every run and in every
process, and each receiver's draw is independent of the others'.

The SNR reported with a received frame uses the passive sonar equation with
spherical spreading and absorption; it is for evaluation and does not decide
the loss (the range curve does, so that a user can set loss rates directly).
"""

from __future__ import annotations

import hashlib
import math

from sim.modem.config import ModemConfig


def loss_probability(range_m: float, cfg: ModemConfig) -> float:
    """Probability that a frame travelling range_m is lost (1 beyond max range)."""
    if range_m > cfg.max_range_m:
        return 1.0
    frac = max(range_m, 0.0) / cfg.max_range_m
    return cfg.loss_at_zero + (cfg.loss_at_max_range - cfg.loss_at_zero) * frac**cfg.loss_exponent


def uniform_draw(seed: int, src: str, seq: int, tx_utime: int, dst: str) -> float:
    """A number in [0, 1) fixed by the frame and its receiver."""
    key = f"{seed}|{src}|{seq}|{tx_utime}|{dst}".encode()
    digest = hashlib.blake2b(key, digest_size=8).digest()
    return int.from_bytes(digest, "big") / 2.0**64


def snr_db(range_m: float, source_level_db: float, cfg: ModemConfig) -> float:
    """The sender's source level minus transmission loss minus our noise [dB]."""
    r = max(range_m, 1.0)
    transmission_loss = 20.0 * math.log10(r) + cfg.absorption_db_per_km * r / 1000.0
    return source_level_db - transmission_loss - cfg.noise_level_db


def frame_duration_s(n_bytes: int, cfg: ModemConfig) -> float:
    """How long the modem is busy sending a frame of n_bytes."""
    return cfg.frame_overhead_s + 8.0 * n_bytes / cfg.bitrate_bps


def distance_3d(a: tuple[float, float, float], b: tuple[float, float, float]) -> float:
    return math.sqrt((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 + (a[2] - b[2]) ** 2)

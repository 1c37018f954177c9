"""The `modem:` section of the simulator configuration.

A configuration without the section has no modem. With it, every key is
checked like the rest of the file (sim.config): errors name the file, line,
column and key, and unknown keys get a did-you-mean.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class ModemConfig:
    enabled: bool = True             # a `modem:` section turns the modem on
    max_frame_bytes: int = 256       # payload limit of one frame
    bitrate_bps: float = 1000.0      # payload bits per second while transmitting
    frame_overhead_s: float = 0.5    # preamble and guard time of every frame
    min_interval_s: float = 0.0      # least time between the starts of two frames
    max_range_m: float = 2000.0      # frames never arrive beyond this 3-D range
    loss_at_zero: float = 0.02       # frame loss probability at 0 m
    loss_at_max_range: float = 0.5   # ... at max_range_m
    loss_exponent: float = 2.0       # shape of the curve between them
    source_level_db: float = 185.0   # re 1 uPa at 1 m, for the reported SNR
    noise_level_db: float = 50.0     # in-band noise, re 1 uPa
    absorption_db_per_km: float = 1.0
    peer_reports: bool = True        # send <V>.PEER_REPORT, publish <V>.PEER.<OTHER>
    status_period_s: float = 1.0     # sim seconds between modem_status_t
    seed: int = -1                   # loss draws; -1 = environment.seed (the world's)


PROBABILITIES = ("loss_at_zero", "loss_at_max_range")
POSITIVE = ("bitrate_bps", "max_range_m", "loss_exponent", "status_period_s")


def parse(doc, node):
    """A ModemConfig from the section's node (None: no section, no modem)."""
    from sim.config import _fill  # here: sim.config imports this module while loading

    if node is None:
        return None
    cfg = _fill(doc, node, "modem", ModemConfig())
    items = doc.mapping(node, "modem")

    def check(name: str, ok: bool, msg: str) -> None:
        key = f"modem.{name}"
        already = any(f": {key}: " in e for e in doc.errors)  # e.g. the generic >= 0 rule
        if name in items and not ok and not already:
            doc.err(items[name][1], key, msg)

    for name in PROBABILITIES:
        check(name, 0.0 <= getattr(cfg, name) <= 1.0, "must be a probability in [0, 1]")
    for name in POSITIVE:
        check(name, getattr(cfg, name) > 0.0, "must be > 0")
    check("max_frame_bytes", 1 <= cfg.max_frame_bytes <= 32767,
          "must be 1..32767 (modem_tx_t.n_bytes is an int16)")
    for name in ("frame_overhead_s", "min_interval_s", "absorption_db_per_km"):
        check(name, getattr(cfg, name) >= 0.0, "must be >= 0")
    return cfg

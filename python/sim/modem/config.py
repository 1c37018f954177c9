"""The `modem:` section of the simulator configuration.

A configuration without the section has no modem. With it, every key is
checked like the rest of the file (confcheck): errors name the file, line,
column and key, unknown keys get a did-you-mean, ranges are declared here.
"""

from __future__ import annotations

from dataclasses import dataclass

from confcheck import Checker, setting


@dataclass
class ModemConfig:
    enabled: bool = True             # a `modem:` section turns the modem on
    # payload limit of one frame (modem_tx_t.n_bytes is an int16)
    max_frame_bytes: int = setting(256, ge=1, le=32767)
    bitrate_bps: float = setting(1000.0, gt=0.0)   # payload bits per second while transmitting
    frame_overhead_s: float = setting(0.5, ge=0.0)  # preamble and guard time of every frame
    min_interval_s: float = setting(0.0, ge=0.0)    # least time between the starts of two frames
    max_range_m: float = setting(2000.0, gt=0.0)    # frames never arrive beyond this 3-D range
    loss_at_zero: float = setting(0.02, ge=0.0, le=1.0)      # frame loss probability at 0 m
    loss_at_max_range: float = setting(0.5, ge=0.0, le=1.0)  # ... at max_range_m
    loss_exponent: float = setting(2.0, gt=0.0)     # shape of the curve between them
    source_level_db: float = 185.0   # re 1 uPa at 1 m, for the reported SNR
    noise_level_db: float = 50.0     # in-band noise, re 1 uPa
    absorption_db_per_km: float = setting(1.0, ge=0.0)
    peer_reports: bool = True        # send <V>.PEER_REPORT, publish <V>.PEER.<OTHER>
    status_period_s: float = setting(1.0, gt=0.0)   # sim seconds between modem_status_t
    seed: int = -1                   # loss draws; -1 = environment.seed (the world's)


def parse(doc: Checker, node) -> ModemConfig | None:
    """A ModemConfig from the section's node (None: no section, no modem)."""
    if node is None:
        return None
    return doc.fill(node, "modem", ModemConfig())

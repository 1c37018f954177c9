"""The `modem:` section of the simulator configuration.

A configuration without the section has no modem. With it, every key is
checked like the rest of the file (confcheck): errors name the file, line,
column and key, unknown keys get a did-you-mean, ranges are declared here.

`wire:` puts a WHOI Micro-Modem's NMEA interface on a pty or TCP port
(sim.devices.micromodem, docs/simulator.md "Devices at the wire").

`profile:` picks a rate profile (PROFILES, after the WHOI Micro-Modem's
rates): frame size, bit rate and per-frame overhead; keys given beside it
override the profile's values.
"""

from __future__ import annotations

import dataclasses
import difflib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from confcheck import Checker, setting
from sim.devices.config import parse_wire


@dataclass
class ModemConfig:
    enabled: bool = True  # a `modem:` section turns the modem on
    profile: str = ""  # rate profile (PROFILES); "" = the keys below
    # payload limit of one frame (modem_tx_t.n_bytes is an int16)
    max_frame_bytes: int = setting(256, ge=1, le=32767)
    bitrate_bps: float = setting(1000.0, gt=0.0)  # payload bits per second while transmitting
    frame_overhead_s: float = setting(0.5, ge=0.0)  # preamble and guard time of every frame
    min_interval_s: float = setting(0.0, ge=0.0)  # least time between the starts of two frames
    max_range_m: float = setting(2000.0, gt=0.0)  # frames never arrive beyond this 3-D range
    loss_at_zero: float = setting(0.02, ge=0.0, le=1.0)  # frame loss probability at 0 m
    loss_at_max_range: float = setting(0.5, ge=0.0, le=1.0)  # ... at max_range_m
    loss_exponent: float = setting(2.0, gt=0.0)  # shape of the curve between them
    source_level_db: float = 185.0  # re 1 uPa at 1 m, for the reported SNR
    noise_level_db: float = 50.0  # in-band noise, re 1 uPa
    absorption_db_per_km: float = setting(1.0, ge=0.0)
    peer_reports: bool = True  # send <V>.PEER_REPORT, publish <V>.PEER.<OTHER>
    status_period_s: float = setting(1.0, gt=0.0)  # sim seconds between modem_status_t
    seed: int = -1  # loss draws; -1 = environment.seed (the world's)
    # the modem at the wire (sim.devices.config.WireConfig, protocol micromodem); None: LCM only
    wire: Any = None


# Rate profiles, one frame per packet, in the class of the WHOI Micro-Modem's
# rates (FSK rate 0: one 32-byte frame at 80 bps; PSK rates: 64 to 256-byte
# frames at hundreds to thousands of bps). frame_overhead_s stands for the
# packet's preamble, probe and guard time.
PROFILES: dict[str, dict[str, float | int]] = {
    "fsk80": {"max_frame_bytes": 32, "bitrate_bps": 80.0, "frame_overhead_s": 1.0},
    "psk250": {"max_frame_bytes": 64, "bitrate_bps": 250.0, "frame_overhead_s": 1.0},
    "psk1300": {"max_frame_bytes": 256, "bitrate_bps": 1300.0, "frame_overhead_s": 1.0},
    "psk5300": {"max_frame_bytes": 256, "bitrate_bps": 5300.0, "frame_overhead_s": 1.0},
}


def with_profile(name: str, **overrides) -> ModemConfig:
    """A ModemConfig of a profile, keys given overriding it (for tests and tools)."""
    return ModemConfig(profile=name, **{**PROFILES[name], **overrides})


def _profile(doc: Checker, node, key: str) -> str | None:
    """The profile named at node (None after reporting a bad one)."""
    name = doc.value(node, key, "")
    if name is dataclasses.MISSING:
        return None
    if name in PROFILES:
        return name
    hint = difflib.get_close_matches(name, list(PROFILES), n=1)
    extra = f"did you mean '{hint[0]}'? " if hint else ""
    doc.err(node, key, f"unknown profile {name!r}; {extra}(known: {', '.join(PROFILES)})")
    return None


def parse(doc: Checker, node, base: Path = Path(".")) -> ModemConfig | None:
    """A ModemConfig from the section's node (None: no section, no modem); base:
    the configuration's folder, for a relative `wire.pty`."""
    if node is None:
        return None
    cfg = ModemConfig()
    items = doc.mapping(node, "modem")
    if "profile" in items:
        name = _profile(doc, items["profile"][1], "modem.profile")
        if name:
            cfg = dataclasses.replace(cfg, profile=name, **PROFILES[name])
    wire = {"wire": lambda n, k: parse_wire(doc, n, k, "modem", base)}
    return doc.fill(node, "modem", cfg, skip=("profile",), special=wire)

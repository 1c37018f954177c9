"""Names that become channel names or command-line words: one rule each.

A vehicle id starts every channel of its vehicle (<ID>.NAV, <ID>.CHASM.PILOT);
the world's own channels start with SIM. and MODEM. (docs/DESIGN "Channels"),
so a vehicle with such an id would write into the world's channels.
"""

from __future__ import annotations

import re

VEHICLE_ID = re.compile(r"[A-Z][A-Z0-9]{0,15}")
WORLD_PREFIXES = ("SIM", "MODEM")  # SIM.CLOCK, SIM.ENV, MODEM.TX, ...
VEHICLE_ID_HINT = "upper-case letters and digits, starting with a letter, at most 16 characters"


def vehicle_id_problem(vid: object) -> str:
    """Why vid cannot be a vehicle id ("" if it can)."""
    if not isinstance(vid, str) or not VEHICLE_ID.fullmatch(vid):
        return f"must be {VEHICLE_ID_HINT} (it starts every channel name)"
    if vid in WORLD_PREFIXES:
        return (
            f"'{vid}' is reserved: the world's channels start with "
            f"{' and '.join(p + '.' for p in WORLD_PREFIXES)} (pick another id, e.g. AUV1)"
        )
    return ""

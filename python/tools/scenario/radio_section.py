"""The scenario's `radio:` section (docs/radio.md): a surface radio between the
shore and the vehicles. With it the launcher starts the radio model
(auv-radio-sim), the shore gateway and one vehicle gateway per vehicle.

    radio:
      bitrate_bps: 115200      # and every other key of sim.radio.link.RadioConfig
      report_period_s: 2.0     # the vehicles' status home while at the surface
      acoustic: {AUV1: 0}      # team index of each vehicle the shore may command acoustically
      peers: true              # the status also goes vehicle to vehicle (PEER_RADIO_REPORT)
      shore_lcm_url: "udpm://239.255.76.68:7667?ttl=0"   # the shore's own LCM (default: the world's)
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

from confcheck import Checker, setting
from sim.radio.link import RadioConfig


@dataclass
class RadioSection(RadioConfig):
    report_period_s: float = setting(2.0, gt=0.0)
    peers: bool = False  # each vehicle's status also goes to its teammates in radio range
    shore_lcm_url: str = ""  # the shore's own LCM ("": the world's); the shore gateway and tools use it
    acoustic: dict[str, int] = field(default_factory=dict)


def parse(c: Checker, node, vehicles: list[str]) -> RadioSection | None:
    """The section (None: no radio); errors are reported on c."""
    if node is None:
        return None

    def acoustic(n, key: str):
        items = c.mapping(n, key)
        out = {}
        for name, (_, vn) in items.items():
            value = c.scalar(vn)
            if name not in vehicles:
                c.err(vn, f"{key}.{name}", f"not a vehicle of the scenario ({', '.join(vehicles)})")
            elif not isinstance(value, int) or isinstance(value, bool) or not 0 <= value <= 14:
                c.err(vn, f"{key}.{name}", "a team index 0 .. 14 (15 is the shore)")
            else:
                out[name] = value
        return out

    return c.fill(node, "radio", RadioSection(), special={"acoustic": acoustic})


def model_settings(r: RadioSection) -> dict[str, object]:
    """The radio model's flags (RadioConfig's fields only)."""
    return {f.name: getattr(r, f.name) for f in dataclasses.fields(RadioConfig)}

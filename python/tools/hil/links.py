"""The device links of one vehicle at the wire: which device speaks on which port,
the simulator's `wire:` keys for them, and the vehicle computer's drivers.

A link is a TCP port on the simulator's host (the vehicle computer connects to
it, as to a serial-to-Ethernet server) or a pseudo-terminal on one machine. Each
vehicle gets a block of ports from `base_port` (docs/hil.md, "Ports").
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

# device -> (where its wire goes in the simulator's configuration, protocol, baud)
# in the order the vehicle computer starts the drivers: the clock first
DEVICES: dict[str, tuple[tuple[str, ...], str, int]] = {
    "timesync": (("time_link",), "pauvt", 115200),
    "gps": (("sensors", "gps"), "nmea", 9600),
    "ahrs": (("sensors", "ahrs"), "nmea", 115200),
    "depth": (("sensors", "depth"), "digiquartz", 9600),
    "dvl": (("sensors", "dvl"), "pd0", 115200),
    "servo": (("actuators",), "maestro", 115200),
    "modem": (("modem",), "micromodem", 19200),
    "payload": (("sonar",), "lcmframe", 115200),
    "payload_looks": (("identify",), "lcmframe", 115200),
}
PORTS_PER_VEHICLE = 10


@dataclass
class Link:
    device: str
    protocol: str
    baud: int
    tcp_port: int = 0  # TCP: the simulator listens on it
    pty: str = ""  # one machine: the pty's link path

    def sim_wire(self) -> dict:
        """The simulator's `wire:` mapping (only the bytes: publish_lcm false)."""
        where = {"tcp": f"*:{self.tcp_port}"} if self.tcp_port else {"pty": self.pty}
        # an input device (the fins) takes no LCM commands beside its bytes (take_lcm); the
        # time link has no LCM message to leave out
        only = {"servo": {"take_lcm": False}, "timesync": {}}.get(self.device, {"publish_lcm": False})
        return {"protocol": self.protocol, **where, "baud": self.baud, **only}

    def driver_port(self, sim_host: str) -> dict:
        """What the driver opens: programs.device_driver's port or tcp."""
        if self.tcp_port:
            return {"tcp": f"{sim_host}:{self.tcp_port}"}
        return {"port": self.pty, "baud": self.baud}


def plan_links(devices: list[str], index: int, base_port: int, pty_dir: Path | None) -> list[Link]:
    """The links of the vehicle at `index` in the scenario: TCP ports from
    base_port + index * PORTS_PER_VEHICLE, or ptys in pty_dir."""
    out = []
    for k, dev in enumerate(d for d in DEVICES if d in devices):
        _, proto, baud = DEVICES[dev]
        if pty_dir is not None:
            out.append(Link(dev, proto, baud, pty=str(pty_dir / dev)))
        else:
            out.append(Link(dev, proto, baud, tcp_port=base_port + index * PORTS_PER_VEHICLE + k))
    return out


def wired_config(cfg: dict, links: list[Link], extra: dict[str, dict]) -> dict:
    """The simulator's configuration with every link's `wire:` (plus extra keys per
    device, e.g. the time link's rate or the servo's table)."""
    out = {**cfg}
    for link in links:
        path = DEVICES[link.device][0]
        node = out
        for key in path[:-1]:
            node[key] = dict(node.get(key) or {})
            node = node[key]
        section = dict(node.get(path[-1]) or {})
        section["wire"] = {**link.sim_wire(), **extra.get(link.device, {})}
        node[path[-1]] = section
    return out

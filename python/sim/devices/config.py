"""A sensor's `wire:` mapping: which protocol, on which port, at which baud.

    sensors:
      gps:
        wire: {protocol: nmea, pty: /tmp/auv1-gps, baud: 9600, publish_lcm: true, talker: GN}

Checked like every setting (confcheck: file:line:col errors, did-you-mean on
unknown keys): the protocol must be one registered for the sensor
(sim.devices.registry), exactly one of `pty` and `tcp`, a standard baud; the
protocol's own keys (its Options) sit beside the common ones.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from confcheck import Checker, Rule, setting
from sim.devices.line import BAUDS
from sim.devices.registry import protocols_of

HOST_PORT = r"(?P<host>[A-Za-z0-9][A-Za-z0-9.-]*|\*):(?P<port>[0-9]{1,5})"


@dataclass
class WireConfig:
    protocol: str = ""  # one registered for the sensor (required)
    pty: str = ""  # path of the symlink to the pty's slave (relative: to the configuration's folder)
    tcp: str = setting("", pattern=HOST_PORT, pattern_hint="HOST:PORT, e.g. 127.0.0.1:4001 (host * : every address)")
    baud: int = setting(9600, one_of=BAUDS)  # the line's rate, 10 bits a byte (TCP too: a serial server's line)
    publish_lcm: bool = True  # true: the LCM message beside the bytes; false: the bytes instead
    queue_bytes: int = setting(65536, ge=1024, le=16777216)  # the port's queue; over it a message is dropped
    options: Any = None  # the protocol's own keys (its Options dataclass), beside these in the file

    @property
    def tcp_address(self) -> tuple[str, int]:
        m = re.fullmatch(HOST_PORT, self.tcp)
        assert m is not None
        host = m["host"]
        return ("" if host == "*" else host), int(m["port"])


COMMON_KEYS = tuple(f.name for f in dataclasses.fields(WireConfig) if f.name != "options")


# an input device (the fins and thruster) publishes nothing: its LCM switch is its own
# option (`take_lcm`), so a `publish_lcm` there is an unknown key, not a silent no-op
INPUT_DEVICE_KEYS = tuple(k for k in COMMON_KEYS if k != "publish_lcm")


def parse_wire(doc: Checker, node, key: str, sensor: str, base: Path, common: tuple = COMMON_KEYS) -> Any:
    """The WireConfig of a sensor's (or another part's: `actuators`) `wire:` value
    (None: absent or false; MISSING after reporting a problem); `common`: the common
    keys it takes."""
    if doc.is_empty(node) or (isinstance(node, yaml.ScalarNode) and doc.scalar(node) is False):
        return None
    if not isinstance(node, yaml.MappingNode):
        doc.err(node, key, "expected a mapping: {protocol: ..., pty: PATH | tcp: HOST:PORT, baud: ...}, or false")
        return dataclasses.MISSING
    items = doc.mapping(node, key)
    protocols = protocols_of(sensor)
    if not protocols:
        doc.err(node, key, f"no device emulator speaks for sensors.{sensor} yet")
        return dataclasses.MISSING
    if "protocol" not in items:
        doc.err(node, key, f"missing required key 'protocol' (one of: {', '.join(protocols)})")
        return dataclasses.MISSING
    errors_before = len(doc.errors)
    pnode = items["protocol"][1]
    proto = doc.value(pnode, f"{key}.protocol", "", Rule(one_of=tuple(protocols)))
    if proto is dataclasses.MISSING:
        return proto
    emulator = protocols[proto]
    opts = emulator.Options()
    opt_keys = {f.name for f in dataclasses.fields(opts)}
    doc.unknown(items, [*common, *opt_keys], key)
    wire = doc.fill(node, key, WireConfig(), skip=set(items) - set(common))
    doc.fill(node, key, opts, skip=set(items) - opt_keys)
    wire.options = opts
    ok = True
    for name, problem in emulator.problems(opts).items():
        doc.err(items[name][1] if name in items else node, f"{key}.{name}", problem)
        ok = False
    if ("pty" in items) == ("tcp" in items):
        doc.err(node, key, "give one port: `pty: PATH` or `tcp: HOST:PORT`" + (", not both" if "pty" in items else ""))
        ok = False
    elif wire.tcp and not 1 <= wire.tcp_address[1] <= 65535:
        doc.err(items["tcp"][1], f"{key}.tcp", f"port must be in [1, 65535], got {wire.tcp_address[1]}")
        ok = False
    elif "pty" in items and not wire.pty:
        doc.err(items["pty"][1], f"{key}.pty", "expected the path of the link to make")
        ok = False
    if wire.pty:
        wire.pty = str(base / wire.pty) if not Path(wire.pty).is_absolute() else wire.pty
    return wire if ok and len(doc.errors) == errors_before else dataclasses.MISSING


def check_distinct(doc: Checker, wires: dict[str, tuple[Any, Any]]) -> None:
    """No two devices on one port: wires is {section key ("sensors.gps", "sonar"):
    (wire node, WireConfig)}."""
    seen: dict[str, str] = {}
    for key, (node, w) in wires.items():
        where = w.pty or f"tcp {w.tcp_address[1]}"
        if where in seen:
            doc.err(node, f"{key}.wire", f"{seen[where]} is on this port already")
        seen[where] = key

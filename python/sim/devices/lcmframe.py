"""lcmframe: an LCM message framed whole on a line, for payloads with no device protocol.

The sidescan's contacts (<V>.CONTACTS) and the identify sensor's looks
(<V>.LOOKS) come from a sonar and its ATR computer, which have no device
protocol to copy here. At the wire (`sonar.wire`, `identify.wire`, protocol
`lcmframe`) the simulator frames each message as the vehicle's driver
(c/drivers/payload, `auv-payload`; layout in c/drivers/payload/lcmframe.h and
docs/drivers.md) reads it:

    A5 4C | T | topic (T bytes) | N (2, big-endian) | payload (N) | CRC-16 (2, big-endian)

the payload being the message's LCM encoding exactly as it would be published,
the CRC CRC-16/CCITT-FALSE over everything before it.
"""

from __future__ import annotations

import binascii
import re
from typing import Any

from sim.devices.emulator import Emulator

SYNC = b"\xa5\x4c"
MAX_TOPIC = 32
MAX_PAYLOAD = 4096  # c/drivers/payload/lcmframe.h LCMFRAME_MAX_PAYLOAD


def crc16(data: bytes) -> int:
    """CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF): b"123456789" -> 0x29B1."""
    return binascii.crc_hqx(data, 0xFFFF)


def frame(topic: str, payload: bytes) -> bytes:
    """One frame of payload (an encoded LCM message) under topic ("CONTACTS")."""
    if not re.fullmatch(r"[A-Z0-9_]{1,%d}" % MAX_TOPIC, topic):
        raise ValueError(f"topic {topic!r}: 1..{MAX_TOPIC} of A-Z, 0-9, _")
    if not 0 < len(payload) <= MAX_PAYLOAD:
        raise ValueError(f"a payload of {len(payload)} bytes: 1..{MAX_PAYLOAD}")
    body = SYNC + bytes([len(topic)]) + topic.encode("ascii") + len(payload).to_bytes(2, "big") + payload
    return body + crc16(body).to_bytes(2, "big")


class _LcmFrame(Emulator):
    protocol = "lcmframe"
    topic = ""

    def encode(self, msg: Any, truth: Any) -> list[bytes]:
        return [frame(self.topic, msg.encode())]


class SonarFrame(_LcmFrame):
    """The sidescan's contacts (`sonar.wire`)."""

    sensor = "sonar"
    topic = "CONTACTS"


class IdentifyFrame(_LcmFrame):
    """The reacquire-identify sensor's looks (`identify.wire`)."""

    sensor = "identify"
    topic = "LOOKS"

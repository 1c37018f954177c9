"""The acoustic commands' authentication (docs/security.md, "Acoustic"; docs/radio.md):
the team link's `command` message carries a 24-bit counter and a 32-bit tag
(mac_hi, mac_lo), auvlcm.auth.acoustic_tag over the message as encoded with the tag
0, under the team's newest key. This is the shore's side; the vehicle's gateway
(auv-radio, c/drivers/radio/radio_acoustic.c) tries every key of its ring (two
during a rotation), each with its own replay window: a frame is run once, only if
a key tags it and its counter is new.

The counter is the shore's clock in whole seconds modulo 2^24 (194 days), kept
strictly increasing within the shore gateway: a restarted shore goes on above its
old counters without keeping state. It wraps after 194 days; rotate the key before
(a new key starts a new window on the vehicle).
"""

from __future__ import annotations

import time

from auvlcm import auth
from auvlcm.team_codec import TeamCodec

MASK24 = 0xFFFFFF


def untagged(codec: TeamCodec, vals: dict) -> bytes:
    """The message's bytes with its tag 0: what the tag covers."""
    return codec.encode("command", {**vals, "mac_hi": 0, "mac_lo": 0})


class Tagger:
    """The shore's side: counters and tags under the ring's newest key."""

    def __init__(self, ring: auth.KeyRing) -> None:
        self.ring = ring
        self.last = -1

    def counter(self) -> int:
        self.last = max(int(time.time()) & MASK24, self.last + 1) & MASK24
        return self.last

    def tag(self, codec: TeamCodec, vals: dict) -> dict:
        t = auth.acoustic_tag(self.ring.signing.secret, untagged(codec, vals), vals["counter"])
        return {**vals, "mac_hi": t >> 16, "mac_lo": t & 0xFFFF}

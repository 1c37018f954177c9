"""A node's radio modem as a byte pipe (docs/radio.md, "The byte pipe").

A real radio modem is a serial line to its host; with `--pipe AUV1=PATH` the
simulated radio gives vehicle AUV1 one too: a pseudo-terminal at PATH (a
symlink to its slave, as the simulator's devices at the wire), where the
vehicle's gateway (`auv-radio`, a driver on c/drivers/common) reads and writes
the frames in the pipe's framing (tools/radio/pipe.py), exactly as it would on
the vehicle. Frames for the node go on the pty instead of RADIO.RX.<NODE>;
what the node writes is taken as if published on RADIO.TX.<NODE>.
"""

from __future__ import annotations

from pathlib import Path

from auv import radio_frame_t
from sim.devices.transport import PtyTransport
from tools.radio.pipe import Deframer, encode

OUT_BYTES = 65536  # frames waiting for the reader: the node's serial buffer


class PipeNode:
    def __init__(self, node: str, path: str | Path) -> None:
        self.node = node
        self.transport = PtyTransport(path)
        self.deframer = Deframer()
        self.out = bytearray()
        self.unheard = 0  # frames with no reader (the gateway not running) or no room
        self.sent = 0

    def fds(self) -> list[int]:
        self.transport.connected()  # notices a reader coming or going
        return self.transport.read_fds()

    def read(self, fd: int) -> list[radio_frame_t]:
        return self.deframer.feed(self.transport.on_readable(fd))

    def write(self, frame_bytes: bytes) -> None:
        data = encode(frame_bytes)
        if not self.transport.connected() or len(self.out) + len(data) > OUT_BYTES:
            self.unheard += 1
            return
        self.out += data
        self.sent += 1
        self.flush()

    def flush(self) -> None:
        if self.out:
            n = self.transport.send(bytes(self.out))
            del self.out[:n]

    def close(self) -> None:
        self.transport.close()

    def summary(self) -> str:
        dropped = dict(self.deframer.dropped)
        return f"{self.node} pipe: {self.sent} frames written, {self.unheard} unheard, dropped {dropped}"


def parse_pipes(text: str) -> dict[str, str]:
    """`AUV1=PATH,AUV2=PATH` -> {node: path}; ValueError if malformed."""
    out: dict[str, str] = {}
    for item in filter(None, text.split(",")):
        node, sep, path = item.partition("=")
        if not sep or not node or not path:
            raise ValueError(f"--pipe: {item!r} is not NODE=PATH")
        out[node] = path
    return out

"""The radio as a byte pipe: how the gateways talk to a real radio modem.

A radio modem (Freewave class) is a transparent serial link: bytes in at one
end come out at the other, or not. Each radio_frame_t goes on it as (the one
definition: docs/radio.md, "The byte pipe"; the vehicle's gateway, auv-radio,
frames it in C, c/drivers/radio/radio_pipe.c, and the tests hold the two
together)

    0xA5 0x5A, length (4 bytes, big endian), the encoded radio_frame_t, CRC-32 (4 bytes)

and the reader finds frames in the byte stream: it skips to the next marker
after anything that does not check (a wrong CRC, a length over MAX_FRAME, a
frame that does not decode), counting what it dropped, so line noise or a
frame cut by a dive costs that frame and nothing after it.

The pipe is a TCP connection (`--tcp HOST:PORT`: a radio's Ethernet port, or
a serial server) or a serial device (`--device PATH`, raw mode, the radio's
own rate). The connection is opened again after it drops.
"""

from __future__ import annotations

import os
import select
import signal
import socket
import struct
import termios
import time
import tty
import zlib
from collections import Counter
from typing import Any, Callable

from auv import radio_frame_t

MARK = b"\xa5\x5a"
MAX_FRAME = 16384  # an encoded radio_frame_t: a 4 KiB chunk and its header fit many times


def encode(frame_bytes: bytes) -> bytes:
    return MARK + struct.pack(">I", len(frame_bytes)) + frame_bytes + struct.pack(">I", zlib.crc32(frame_bytes))


class Deframer:
    """Bytes in, radio frames out; what does not check is counted and skipped."""

    def __init__(self) -> None:
        self.buf = bytearray()
        self.dropped: Counter[str] = Counter()

    def feed(self, data: bytes) -> list[radio_frame_t]:
        self.buf += data
        out: list[radio_frame_t] = []
        while True:
            start = self.buf.find(MARK)
            if start < 0:
                if len(self.buf) > 1:
                    self.dropped["noise bytes"] += len(self.buf) - 1
                    del self.buf[:-1]  # a marker may begin in the last byte
                return out
            if start:
                self.dropped["noise bytes"] += start
                del self.buf[:start]
            if len(self.buf) < 6:
                return out
            (n,) = struct.unpack(">I", self.buf[2:6])
            if n > MAX_FRAME:
                self._skip("too long")
                continue
            if len(self.buf) < 10 + n:
                return out
            body, (crc,) = bytes(self.buf[6 : 6 + n]), struct.unpack(">I", self.buf[6 + n : 10 + n])
            if zlib.crc32(body) != crc:
                self._skip("bad CRC")
                continue
            del self.buf[: 10 + n]
            try:
                out.append(radio_frame_t.decode(body))
            except (ValueError, struct.error):
                self.dropped["undecodable"] += 1

    def _skip(self, why: str) -> None:
        self.dropped[why] += 1
        del self.buf[:2]  # past this marker: the next one may start a good frame


class BytePipe:
    """A TCP connection or a serial device, reopened when it drops."""

    def __init__(self, tcp: str = "", device: str = "") -> None:
        self.tcp, self.device = tcp, device
        self.fd: int | None = None
        self.sock: socket.socket | None = None
        self.deframer = Deframer()
        self.reopened = 0

    def open(self) -> bool:
        try:
            if self.tcp:
                host, port = self.tcp.rsplit(":", 1)
                self.sock = socket.create_connection((host, int(port)), timeout=2.0)
                self.sock.setblocking(False)
                self.fd = self.sock.fileno()
            else:
                self.fd = os.open(self.device, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
                if os.isatty(self.fd):
                    tty.setraw(self.fd, termios.TCSANOW)
        except (OSError, ValueError):
            self.close()
            return False
        self.reopened += 1
        return True

    def close(self) -> None:
        if self.sock is not None:
            self.sock.close()
        elif self.fd is not None:
            os.close(self.fd)
        self.sock, self.fd = None, None

    def write(self, frame_bytes: bytes) -> bool:
        """Send one frame; False if the pipe is down (the frame is lost, as on the air)."""
        if self.fd is None and not self.open():
            return False
        try:
            data = encode(frame_bytes)
            while data:
                n = os.write(self.fd, data) if self.sock is None else self.sock.send(data)
                data = data[n:]
            return True
        except BlockingIOError:
            return False  # the radio's buffer is full: dropped, the protocol resends
        except OSError:
            self.close()
            return False

    def read(self) -> list[radio_frame_t]:
        if self.fd is None:
            return []
        try:
            data = os.read(self.fd, 65536) if self.sock is None else self.sock.recv(65536)
        except BlockingIOError:
            return []
        except OSError:
            self.close()
            return []
        if not data and self.sock is not None:  # the far end closed
            self.close()
            return []
        return self.deframer.feed(data)


def serve(lc, pipe: BytePipe | None, on_frame, tick, stop: list) -> None:
    """A gateway's loop: LCM, the pipe (reopened every second while down), tick()."""
    next_open = 0.0
    while not stop:
        fds = [lc.fileno()] + ([pipe.fd] if pipe is not None and pipe.fd is not None else [])
        try:
            ready, _, _ = select.select(fds, [], [], 0.02)
            if lc.fileno() in ready:
                lc.handle()
        except OSError:  # EINTR from the signal that stops us: the loop checks
            continue
        if pipe is not None:
            if pipe.fd is not None and pipe.fd in ready:
                for f in pipe.read():
                    on_frame("RADIO.PIPE", f)
            elif pipe.fd is None and time.monotonic() >= next_open:
                next_open = time.monotonic() + 1.0
                pipe.open()
        tick()


def run_gateway(program: str, url: str, make: Callable[[Any], Any]) -> Any:
    """The shore gateway process's life: its LCM (a receive buffer big
    enough for an upload's many datagrams: none may be lost), the gateway make(lc)
    builds, "ready" once subscribed (what is published from then on is heard), the
    loop until SIGINT or SIGTERM; returns the gateway for its summary."""
    import lcm

    from auvlcm.url import with_receive_buffer

    lc = lcm.LCM(with_receive_buffer(url))
    gw = make(lc)
    stop: list[int] = []
    signal.signal(signal.SIGINT, lambda *_: stop.append(1))
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    print(f"{program}: ready", flush=True)
    serve(lc, gw.pipe, gw._on_frame, gw.tick, stop)
    return gw

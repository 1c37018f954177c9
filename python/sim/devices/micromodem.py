"""A WHOI Micro-Modem at the wire: the modem side of the NMEA subset the vehicle's
bridge speaks (c/drivers/modem/mm_msg.h, docs/drivers.md "WHOI Micro-Modem").

I/O-free: bytes from the host in, bytes to the host out, every call given the sim
time. The port (python/sim/devices/port.py) carries the bytes; the simulator's
acoustic modem (python/sim/modem) carries the frames: `take_outbox()` gives the
packets the host sent, `hear()` turns a frame the water delivered into what the
modem prints.

What it does, per host sentence:

- `$CCCFG,NAME,VALUE` sets a parameter and answers `$CACFG,NAME,VALUE`;
  `$CCCFQ,NAME` (or ALL) answers `$CACFG` lines.
- `$CCCYC,0,SRC,DEST,RATE,ACK,N` (SRC must be this modem) echoes `$CACYC`, then asks
  for each frame with `$CADRQ,HHMMSS,SRC,DEST,ACK,BYTES,F#`; each `$CCTXD` is echoed
  `$CATXD,SRC,DEST,ACK,N`; after the last frame the packet goes into the water. A
  `$CCTXD` outside a cycle is buffered for the next one (no request for it then).
- anything it cannot take answers `$CAERR,HHMMSS,MODULE,NUMBER,TEXT`: a bad checksum,
  an unknown sentence, a bad address, rate or hex, data longer than the frame, a
  host that does not answer a data request within DTO seconds.
- `$CAREV,HHMMSS,INIT,VERSION` at the first call, then `$CAREV,HHMMSS,AUV,VERSION`
  every `heartbeat_s`: the real modem's heartbeat.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from auv import modem_rx_t, modem_tx_t
from confcheck import setting
from sim.devices.emulator import Emulator

# Index = rate (packet type): rate 0 FH-FSK, 1-5 PSK.
FRAME_BYTES = (32, 64, 64, 256, 256, 256)
FRAMES = (1, 3, 3, 2, 2, 8)
BROADCAST = 0
MAX_ADDRESS = 127


def checksum(body: str) -> str:
    c = 0
    for ch in body.encode("ascii"):
        c ^= ch
    return f"{c:02X}"


def sentence(body: str) -> bytes:
    """`$` body `*hh` CR LF."""
    return f"${body}*{checksum(body)}\r\n".encode("ascii")


def hhmmss(t: float) -> str:
    s = int(t) % 86400
    return f"{s // 3600:02d}{s // 60 % 60:02d}{s % 60:02d}"


@dataclass
class Packet:
    """A packet the host asked the modem to send: its frames, in order."""

    t: float
    src: int
    dest: int
    rate: int
    ack: int
    frames: list[bytes]


@dataclass
class _Cycle:
    src: int
    dest: int
    rate: int
    ack: int
    n: int
    frames: list[bytes] = field(default_factory=list)
    asked_at: float = 0.0


class BadInput(Exception):
    """A host sentence the modem refuses: its CAERR module, number and text."""

    def __init__(self, module: str, number: int, text: str) -> None:
        super().__init__(text)
        self.module, self.number, self.text = module, number, text


def _int(v: str, lo: int, hi: int, what: str) -> int:
    try:
        n = int(v, 10)
    except ValueError:
        raise BadInput("NMEA", 3, f"bad {what}: '{v}'") from None
    if not lo <= n <= hi:
        raise BadInput("NMEA", 3, f"bad {what}: {n}")
    return n


def _hex(v: str) -> bytes:
    if len(v) % 2:
        raise BadInput("NMEA", 4, "odd hex length")
    try:
        return bytes.fromhex(v)
    except ValueError:
        raise BadInput("NMEA", 4, "bad hex") from None


class MicroModem:
    def __init__(self, address: int = 1, revision: str = "0.94.0.4", heartbeat_s: float = 10.0) -> None:
        self.params: dict[str, str] = {"SRC": str(address), "CST": "1", "XST": "0", "DTO": "5", "REV": "1"}
        self.revision = revision
        self.heartbeat_s = heartbeat_s
        self._next_rev: float | None = None
        self._line = bytearray()
        self._cycle: _Cycle | None = None
        self._buffered: list[tuple[int, int, int, bytes]] = []  # CCTXD outside a cycle
        self._outbox: list[Packet] = []
        self.errors = 0

    @property
    def address(self) -> int:
        return int(self.params["SRC"])

    # ---- host -> modem

    def feed(self, data: bytes, t: float) -> bytes:
        """Bytes from the host; returns the modem's answers."""
        out = bytearray(self.tick(t))
        for b in data:
            if b in (0x0D, 0x0A):
                if self._line:
                    out += self._line_in(self._line.decode("ascii", "replace"), t)
                    self._line.clear()
            elif len(self._line) < 1000:
                self._line.append(b)
        return bytes(out)

    def _line_in(self, line: str, t: float) -> bytes:
        start = line.rfind("$")
        if start < 0:
            return self._err(t, BadInput("NMEA", 1, "no sentence"))
        line = line[start + 1 :]
        body, star, cs = line.partition("*")
        if not star or cs.upper() != checksum(body):
            return self._err(t, BadInput("NMEA", 1, "bad checksum"))
        f = body.split(",")
        try:
            handler = {
                "CCCFG": self._cfg,
                "CCCFQ": self._cfq,
                "CCCYC": self._cyc,
                "CCTXD": self._txd,
                "CCMPC": self._mpc,
            }.get(f[0])
            if handler is None:
                raise BadInput("NMEA", 2, f"unknown sentence {f[0]}")
            return handler(f[1:], t)
        except BadInput as e:
            return self._err(t, e)

    def _err(self, t: float, e: BadInput) -> bytes:
        self.errors += 1
        text = e.text.replace("*", " ").replace("$", " ")
        return sentence(f"CAERR,{hhmmss(t)},{e.module},{e.number},{text}")

    def _cfg(self, f: list[str], t: float) -> bytes:
        if len(f) < 2 or not f[0] or not f[1]:
            raise BadInput("NMEA", 3, "CCCFG: missing fields")
        name, value = f[0], f[1]
        if not name.isalnum() or not name.isupper():
            raise BadInput("NMEA", 3, f"CCCFG: bad name '{name}'")
        if name == "SRC":
            value = str(_int(value, 0, MAX_ADDRESS, "address"))
        self.params[name] = value
        return sentence(f"CACFG,{name},{value}")

    def _cfq(self, f: list[str], t: float) -> bytes:
        if not f or not f[0]:
            raise BadInput("NMEA", 3, "CCCFQ: missing fields")
        names = sorted(self.params) if f[0] == "ALL" else [f[0]]
        if any(n not in self.params for n in names):
            raise BadInput("NMEA", 3, f"CCCFQ: unknown parameter {f[0]}")
        return b"".join(sentence(f"CACFG,{n},{self.params[n]}") for n in names)

    def _cyc(self, f: list[str], t: float) -> bytes:
        if len(f) < 6 or not all(f[:6]):
            raise BadInput("CYC", 1, "CCCYC: missing fields")
        src = _int(f[1], 0, MAX_ADDRESS, "address")
        dest = _int(f[2], 0, MAX_ADDRESS, "address")
        rate = _int(f[3], 0, len(FRAMES) - 1, "rate")
        ack = _int(f[4], 0, 1, "ack flag")
        n = _int(f[5], 1, FRAMES[rate], "frame count")
        if src != self.address:
            raise BadInput("CYC", 2, f"ADR1 {src} is not this modem ({self.address}): polling is not emulated")
        if self._cycle is not None:
            raise BadInput("CYC", 3, "a cycle is already under way")
        c = _Cycle(src, dest, rate, ack, n)
        out = bytearray(sentence(f"CACYC,0,{src},{dest},{rate},{ack},{n}"))
        # frames the host wrote before the cycle go first, without a request
        while self._buffered and len(c.frames) < n:
            c.frames.append(self._buffered.pop(0)[3][: FRAME_BYTES[rate]])
        self._cycle = c
        out += self._next_request(t)
        return bytes(out)

    def _next_request(self, t: float) -> bytes:
        c = self._cycle
        assert c is not None
        if len(c.frames) == c.n:
            self._outbox.append(Packet(t, c.src, c.dest, c.rate, c.ack, c.frames))
            self._cycle = None
            return b""
        c.asked_at = t
        return sentence(f"CADRQ,{hhmmss(t)},{c.src},{c.dest},{c.ack},{FRAME_BYTES[c.rate]},{len(c.frames) + 1}")

    def _txd(self, f: list[str], t: float) -> bytes:
        if len(f) != 4:
            raise BadInput("NMEA", 3, "CCTXD: expected SRC,DEST,ACK,HEX")
        src = _int(f[0], 0, MAX_ADDRESS, "address")
        dest = _int(f[1], 0, MAX_ADDRESS, "address")
        ack = _int(f[2], 0, 1, "ack flag")
        data = _hex(f[3])
        c = self._cycle
        limit = FRAME_BYTES[c.rate] if c else max(FRAME_BYTES)
        if len(data) > limit:
            raise BadInput("NMEA", 5, f"CCTXD: {len(data)} bytes is over the {limit}-byte frame")
        echo = sentence(f"CATXD,{src},{dest},{ack},{len(data)}")
        if c is None:
            self._buffered.append((src, dest, ack, data))
            return echo
        c.frames.append(data)
        return echo + self._next_request(t)

    def _mpc(self, f: list[str], t: float) -> bytes:
        if len(f) < 2:
            raise BadInput("NMEA", 3, "CCMPC: missing fields")
        src, dest = _int(f[0], 0, MAX_ADDRESS, "address"), _int(f[1], 0, MAX_ADDRESS, "address")
        return sentence(f"CAMPC,{src},{dest}")  # the echo; the ping itself is not emulated

    # ---- time, and the water

    def tick(self, t: float) -> bytes:
        """The heartbeat, and a host too slow to answer a data request."""
        out = bytearray()
        if self._next_rev is None:
            out += sentence(f"CAREV,{hhmmss(t)},INIT,{self.revision}")
            self._next_rev = t
        if t >= self._next_rev:
            out += sentence(f"CAREV,{hhmmss(t)},AUV,{self.revision}")
            self._next_rev = t + self.heartbeat_s
        c = self._cycle
        if c is not None and t - c.asked_at > float(self.params.get("DTO", "5")):
            self._cycle = None
            out += self._err(t, BadInput("CYC", 4, "data request timed out"))
        return bytes(out)

    def take_outbox(self) -> list[Packet]:
        """The packets sent since the last call, for the simulator's acoustic modem."""
        out, self._outbox = self._outbox, []
        return out

    def hear(self, t: float, src: int, dest: int, rate: int, frames: list[bytes], snr_db: float) -> bytes:
        """A packet the water delivered: what the modem prints (nothing when it is
        for another modem). bad frames (None) are counted in CACST."""
        if dest not in (BROADCAST, self.address) or src == self.address:
            return b""
        out = bytearray(sentence(f"CACYC,0,{src},{dest},{rate},0,{len(frames)}"))
        for i, data in enumerate(frames, start=1):
            out += sentence(f"CARXD,{src},{dest},0,{i},{data[: FRAME_BYTES[rate]].hex().upper()}")
        if self.params.get("CST", "1") != "0":
            out += sentence(self._cst(t, src, dest, rate, len(frames), snr_db))
        return bytes(out)

    def _cst(self, t: float, src: int, dest: int, rate: int, n: int, snr_db: float) -> str:
        """A version-0 CACST: mode, TOA, clock, MFD peak/power/ratio/SPL, AGN, four
        shifts, rate, src, dest, PSK error, packet type, frames, bad frames, SNR
        (RSS, in, out, symbols), MSE, DQF, Doppler, noise, carrier, bandwidth."""
        toa = f"{hhmmss(t)}.{int(round((t % 1) * 10000)) % 10000:04d}"
        snr = f"{snr_db:.1f}"
        return (
            f"CACST,0,{toa},0,1000,20,100,100,70,0,0,0,0,{rate},{src},{dest},0,{rate},{n},0,"
            f"{snr},{snr},{snr},0,-20,100,0.0,50,25000,5000"
        )

    def acknowledge(self, t: float, src: int, frame: int = 1) -> bytes:
        """`$CAACK` when the addressee `src` acknowledged our frame (the water's model
        decides whether the ack came back)."""
        return sentence(f"CAACK,{src},{self.address},{frame}")


# ---- the modem in the simulator: the emulator on a port, frames to and from the water

TABLE_ENTRY = re.compile(r"([A-Za-z0-9_-]{1,31})=([0-9]{1,3})")


def parse_table(spec: str) -> dict[str, int]:
    """`AUV1=1,AUV2=2`: vehicle ids to modem addresses 1..127, the rules of
    auv-modem's --table (c/drivers/modem/mm_table.c). ValueError says what is wrong."""
    table: dict[str, int] = {}
    for entry in spec.split(","):
        m = TABLE_ENTRY.fullmatch(entry)
        if not m:
            raise ValueError(f"'{entry}' is not VEHICLE=ADDRESS")
        name, address = m[1], int(m[2])
        if not 1 <= address <= MAX_ADDRESS:
            raise ValueError(f"{name}: address {address} is not in 1..127 (0 is the broadcast address)")
        if name in table or address in table.values():
            raise ValueError(f"{name}={address}: a vehicle or an address given twice")
        table[name] = address
    return table


@dataclass
class MicroModemOptions:
    # vehicle ids to modem addresses, the same as every vehicle's auv-modem --table (required)
    table: str = ""
    kind: int = setting(2, ge=0, le=127)  # the modem_tx_t kind of the frames it sends (the wire carries none)
    heartbeat_s: float = setting(10.0, gt=0.0, le=3600.0)  # CAREV every so often
    revision: str = "0.94.0.4"  # CAREV's version


class MicroModemWire(Emulator):
    """The Micro-Modem as the simulator's acoustic modem's device (sim.modem.node):
    packets the host sent become modem_tx_t for the water, frames the water
    delivered become what the modem prints. One frame per packet: the water
    carries one frame per acoustic frame (a packet of several is refused, counted)."""

    sensor = "modem"
    protocol = "micromodem"
    Options = MicroModemOptions
    options: MicroModemOptions

    @classmethod
    def problems(cls, options: MicroModemOptions) -> dict[str, str]:
        if not options.table:
            return {"table": "required: VEHICLE=ADDRESS,... as auv-modem's --table"}
        try:
            parse_table(options.table)
        except ValueError as e:
            return {"table": str(e)}
        return {}

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.table = parse_table(self.options.table)
        if ctx.vehicle not in self.table:
            raise ValueError(f"modem.wire.table: vehicle {ctx.vehicle} is not in '{self.options.table}'")
        self.by_address = {a: v for v, a in self.table.items()}
        self.modem = MicroModem(self.table[ctx.vehicle], self.options.revision, self.options.heartbeat_s)
        self.seq = 0
        self.refused = 0  # packets the water cannot carry (several frames, an unknown address)
        self.heard = 0  # frames printed to the host

    def receive(self, data: bytes, t: float) -> None:
        out = self.modem.feed(data, t)
        if out:
            self.send(out, t)

    def tick(self, t: float) -> None:
        """Every physics step: the heartbeat and the data-request timeout."""
        out = self.modem.tick(t)
        if out:
            self.send(out, t)

    def take_frames(self) -> list[modem_tx_t]:
        """The packets the host sent since the last call, as the water's frames."""
        out = []
        for p in self.modem.take_outbox():
            dst = "" if p.dest == BROADCAST else self.by_address.get(p.dest)
            if len(p.frames) != 1 or dst is None or not p.frames[0]:
                self.refused += 1
                continue
            self.seq += 1
            m = modem_tx_t()
            m.utime = int(round(p.t * 1e6))
            m.vehicle, m.dst_vehicle, m.seq, m.kind = self.ctx.vehicle, dst, self.seq, self.options.kind
            m.n_bytes, m.payload = len(p.frames[0]), bytes(p.frames[0])
            out.append(m)
        return out

    def hear_frame(self, t: float, rx: modem_rx_t) -> None:
        """A frame the water delivered to this vehicle: CACYC, CARXD, CACST on the line.
        Its rate: the smallest whose frame holds it (the water does not say)."""
        src = self.table.get(rx.src_vehicle)
        if src is None:
            self.refused += 1
            return
        dest = BROADCAST if not rx.dst_vehicle else self.table.get(rx.dst_vehicle, BROADCAST)
        rate = next((r for r, n in enumerate(FRAME_BYTES) if n >= rx.n_bytes), len(FRAME_BYTES) - 1)
        out = self.modem.hear(t, src, dest, rate, [bytes(rx.payload)], rx.snr_db)
        if out:
            self.heard += 1
            self.send(out, t)

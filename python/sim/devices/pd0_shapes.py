"""PD0 in the shapes of RDI's real instruments and their PC programs, from the
emulator's own ensembles (sim.devices.pd0): what a driver meets beyond our
emulator's Workhorse. Each function returns the bytes of a short stream; the
hostile corpus tests/drivers/corpus/pd0/ is written from them
(``python -m sim.devices.pd0_shapes DIR``) and the driver must decode every
ensemble of each, refusing none (docs/drivers.md, "DVL: Teledyne RDI PD0").

- WinRiver II: 132 cells and 60 NMEA sentences (0x2022 each) with its 0x2101
  navigation type, 68 data types in one ensemble;
- a Workhorse with the waves option: 7F 79 waves packets between ensembles;
- an Ocean Surveyor under VMDAS: a 60-byte variable leader with no Y2K clock,
  an 81-byte bottom track, the fixed attitude types 0x3000 and 0x30D8;
- a Sentinel V: a 25-degree beam angle in the fixed leader's byte, its
  0x7000-0x7004 types and beam 5 (0x0A00, 0x0F01), the matrix 0x3200;
- WinRiver II again: a count restarted one back (127, then 127 three minutes
  later), a new ping and not a repeat;
- a recording that starts inside an ensemble.
"""

from __future__ import annotations

import struct
import sys
from pathlib import Path

from sim.devices.pd0 import Pd0Config, Pd0Encoder, assemble, split

ZDA = b"$GPZDA,080918.72*47\r\n"  # short: the corpus is fuzzed, and its size is the fuzzer's time


def _measurement(mode_bottom: bool = True):
    from auv import dvl_t  # the generated types: imported where used

    m = dvl_t()
    m.vehicle = "AUV1"
    m.mode = dvl_t.MODE_BOTTOM_LOCK if mode_bottom else dvl_t.MODE_WATER_TRACK
    m.velocity_mps = [1.2, 0.1, 0.02]
    m.beam_range_m = [14.0, 14.5, 15.0, 15.5]
    return m


def _ensembles(cfg: Pd0Config, count: int, t0: float = 100.0, first: int = 1, bottom: bool = True) -> list[list[bytes]]:
    """The data types of ``count`` ensembles of the emulator, 0.5 s apart, in
    bottom lock (or water track: the velocity in the profile's cells)."""
    enc = Pd0Encoder(cfg)
    out = []
    for i in range(count):
        e = enc.ensemble(_measurement(bottom), 0.02, -0.03, 1.1, t0 + 0.5 * i, number=first + i)
        out.append(split(e))
    return out


def _type(ident: int, length: int, fill: int = 0) -> bytes:
    return struct.pack("<H", ident) + bytes([fill]) * (length - 2)


def _nmea(sentence: bytes) -> bytes:
    """WinRiver II's 0x2022: its NMEA ID (107: ZDA), the length, a time, the sentence."""
    return struct.pack("<HHH8s", 0x2022, 107, len(sentence), b"\0" * 8) + sentence


def winriver_many_types() -> bytes:
    (types,) = _ensembles(Pd0Config(frame="earth", n_cells=132, beam_angle_deg=20.0), 1, first=224)
    return assemble(types + [_nmea(ZDA)] * 60 + [_type(0x2101, 84)])


def waves_between() -> bytes:
    def waves(n: int) -> bytes:
        return assemble([struct.pack("<H", 0x0103) + bytes((7 * i) & 0x7E for i in range(n)), _type(0x0203, 40)], 0x79)

    a, b = (assemble(t) for t in _ensembles(Pd0Config(frame="beam"), 2))
    return waves(84) + a + waves(70) + waves(71) + b


def ocean_surveyor() -> bytes:
    data = b""
    for fixed, variable, *rest in _ensembles(Pd0Config(frame="beam", n_cells=30), 1):
        fixed = fixed[:4] + struct.pack("<H", 0x0248) + fixed[6:] + b"\0"  # 75 kHz, 30 degrees; 60 bytes
        bottom = rest[-1][:81]  # through the range MSBs
        data += assemble([fixed, variable[:60], *rest[:-1], bottom, _type(0x3000, 34), _type(0x30D8, 52)])
    return data


def sentinel_v() -> bytes:
    data = b""
    cfg = Pd0Config(frame="beam", n_cells=20, beam_angle_deg=25.0)
    for fixed, variable, *rest in _ensembles(cfg, 2, bottom=False):
        extra = [_type(0x0A00, 42), _type(0x0F01, 40), _type(0x3200, 34)]
        extra += [_type(0x7000, 16), _type(0x7001, 58), _type(0x7002, 16), _type(0x7004, 10)]
        data += assemble([fixed + b"\0", variable + b"\0", *rest[:-1], *extra])  # no bottom track
    return data


def count_restarted() -> bytes:
    cfg = Pd0Config(frame="ship")
    a = _ensembles(cfg, 1, t0=100.0, first=127)[0]
    b = _ensembles(cfg, 2, t0=270.0, first=127)
    return assemble(a) + b"".join(assemble(t) for t in b)


def starts_inside_an_ensemble() -> bytes:
    a, b, c = (assemble(t) for t in _ensembles(Pd0Config(frame="instrument"), 3))
    return a[len(a) // 2 :] + b + c


def records(data: bytes) -> list[bytes]:
    """A stream cut into its ensembles and waves packets (whole, their sums
    good) and the bytes between them (one piece per run)."""
    out: list[bytes] = []
    i = start = 0
    while i + 4 <= len(data):
        n = struct.unpack_from("<H", data, i + 2)[0]
        whole = data[i] == 0x7F and data[i + 1] in (0x7F, 0x79) and i + n + 2 <= len(data) and n >= 8
        if whole and sum(data[i : i + n]) & 0xFFFF == struct.unpack_from("<H", data, i + n)[0]:
            if start < i:
                out.append(data[start:i])
            out.append(data[i : i + n + 2])
            i = start = i + n + 2
        else:
            i += 1
    if start < len(data):
        out.append(data[start:])
    return out


def renumber(data: bytes, first: int) -> bytes:
    """The stream with its ensembles numbered first, first + 1, ... (24 bits,
    in the variable leader's number and MSB byte), the rest as it was."""
    out, number = b"", first
    for r in records(data):
        if r[:2] == b"\x7f\x7f" and len(r) > 8:
            types = split(r)
            k = next(i for i, t in enumerate(types) if t[:2] == b"\x80\x00")
            v = bytearray(types[k])
            v[2:4] = struct.pack("<H", number & 0xFFFF)
            v[11] = (number >> 16) & 0xFF
            types[k] = bytes(v)
            r = assemble(types)
            number += 1
        out += r
    return out


# file name -> (bytes, the ensembles the driver decodes from them)
SHAPES = {
    "winriver_many_types.pd0": (winriver_many_types, 1),
    "waves_between.pd0": (waves_between, 2),
    "ocean_surveyor.pd0": (ocean_surveyor, 1),
    "sentinel_v.pd0": (sentinel_v, 2),
    "count_restarted.pd0": (count_restarted, 3),
    "starts_inside_an_ensemble.pd0": (starts_inside_an_ensemble, 2),
}


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print("usage: python -m sim.devices.pd0_shapes DIR", file=sys.stderr)
        return 2
    out = Path(argv[0])
    for name, (make, _) in SHAPES.items():
        (out / name).write_bytes(make())
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

"""NMEA 0183 as a device writes it: checksums, sentences, coordinates, UTC fields.

Every emulator of an NMEA device (the GPS; an AHRS or the Micro-Modem later)
builds its sentences here, so all of them agree on the format the drivers
parse (c/drivers/common/nmea.c).
"""

from __future__ import annotations

from datetime import datetime, timedelta, timezone
from typing import Iterable

MINUTE_DIGITS = 5  # ddmm.mmmmm: 1e-5 minute is about 2 cm of latitude


def checksum(body: str) -> str:
    """The *hh of a sentence: XOR of the bytes between '$' and '*', two upper-case hex digits."""
    x = 0
    for b in body.encode("ascii"):
        x ^= b
    return f"{x:02X}"


def sentence(address: str, fields: Iterable[str]) -> bytes:
    """$ADDRESS,f1,f2,...*hh CR LF."""
    body = ",".join([address, *fields])
    return f"${body}*{checksum(body)}\r\n".encode("ascii")


def _degrees_minutes(value: float, deg_width: int, digits: int) -> str:
    scale = 10**digits
    total = round(abs(value) * 60 * scale)  # in units of the last digit: no 60.00000 minutes
    deg, rest = divmod(total, 60 * scale)
    minutes, frac = divmod(rest, scale)
    return f"{deg:0{deg_width}d}{minutes:02d}.{frac:0{digits}d}"


def latitude(deg: float, digits: int = MINUTE_DIGITS) -> tuple[str, str]:
    """ddmm.mmmmm (`digits` decimals of the minute) and N or S."""
    return _degrees_minutes(deg, 2, digits), "N" if deg >= 0 else "S"


def longitude(deg: float, digits: int = MINUTE_DIGITS) -> tuple[str, str]:
    """dddmm.mmmmm (`digits` decimals of the minute) and E or W."""
    return _degrees_minutes(deg, 3, digits), "E" if deg >= 0 else "W"


def utc_at(start: datetime, utime_us: int) -> datetime:
    """The UTC time of a sim time stamp [us], sim time 0 being start; to the
    centisecond the sentences carry (rounded, carrying into the date)."""
    t = start + timedelta(microseconds=utime_us)
    cs = round(t.microsecond / 10000)
    return t.replace(microsecond=0) + timedelta(milliseconds=10 * cs)


def hhmmss(t: datetime) -> str:
    """hhmmss.ss"""
    return f"{t.hour:02d}{t.minute:02d}{t.second:02d}.{t.microsecond // 10000:02d}"


def ddmmyy(t: datetime) -> str:
    return f"{t.day:02d}{t.month:02d}{t.year % 100:02d}"


def parse_utc(text: str) -> datetime:
    """YYYY-MM-DDTHH:MM:SSZ as an aware UTC datetime (ValueError if not a real date)."""
    return datetime.strptime(text, "%Y-%m-%dT%H:%M:%SZ").replace(tzinfo=timezone.utc)

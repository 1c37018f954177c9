"""A Teledyne RDI DVL at the wire: the simulator's DVL measurement (sim.sensors'
``Dvl``, a ``dvl_t``) and the true attitude as one PD0 ensemble, the binary
format of the Workhorse/Pathfinder "Commands and Output Data Format" manuals:
header, fixed leader, variable leader, velocity, correlation, echo intensity,
percent good, bottom track and the checksum (docs/drivers.md, "DVL: Teledyne
RDI PD0").

The unit it imitates: 4 beams in a convex Janus at 30 degrees, looking down,
beam 3 forward; its velocities in the earth, ship or instrument (or beam) frame
as configured. PD0 velocities are the bottom's (bottom track) or the water's
(profile) velocity relative to the DVL, so the vehicle's velocity is written
negated. The driver's decoder (c/drivers/dvl) reverses every step; the tests
read these bytes with it and with dolfyn.
"""

from __future__ import annotations

import datetime as dt
import math
import struct
from collections.abc import Sequence
from dataclasses import dataclass

FRAMES = {"beam": 0, "instrument": 1, "ship": 2, "earth": 3}
INVALID = -32768  # PD0's bad-velocity marker
# The simulator's beams (sim.sensors.instruments.Dvl: forward, aft, starboard,
# port) are RDI's beams 3, 4, 2 and 1 of a down-looking convex head: the index
# of each RDI beam in the simulator's order.
SIM_INDEX_OF_BEAM = (3, 2, 0, 1)
# Firmware 51.41 (a Workhorse): its leaders are the long ones, with the
# serial number, the beam angle byte, the Y2K clock and the range MSBs.
FIRMWARE = (51, 41)
# The RTC of a simulated DVL: this date plus the simulation time, unless the
# time is already seconds since 1970.
RTC_EPOCH = dt.datetime(2026, 1, 1, tzinfo=dt.timezone.utc)


@dataclass
class Pd0Config:
    frame: str = "earth"  # earth, ship, instrument or beam
    beam_angle_deg: float = 30.0
    n_cells: int = 8
    cell_size_m: float = 1.0
    blank_m: float = 0.5
    tilts_used: bool = True  # EX bit 2: pitch and roll in the ship and earth frames
    three_beam: bool = True  # EX bit 1
    serial_number: int = 31
    salinity_ppt: int = 35
    sound_speed_mps: int = 1500


def _attitude_matrix(h: float, p: float, r: float) -> list[list[float]]:
    """RDI's M: the DVL's ship axes (X stbd, Y fwd, Z up) to earth (E, N, U)."""
    ch, sh, cp, sp, cr, sr = math.cos(h), math.sin(h), math.cos(p), math.sin(p), math.cos(r), math.sin(r)
    return [
        [ch * cr + sh * sp * sr, sh * cp, ch * sr - sh * sp * cr],
        [-sh * cr + ch * sp * sr, ch * cp, -sh * sr - ch * sp * cr],
        [-cp * sr, sp, cp * cr],
    ]


def _mul(m: list[list[float]], v: Sequence[float]) -> list[float]:
    return [m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3)]


def body_to_ned(phi: float, th: float, psi: float, v: Sequence[float]) -> list[float]:
    """The vehicle's body axes (x fwd, y stbd, z down) to north, east, down (ZYX)."""
    cphi, sphi, cth, sth, cpsi, spsi = (
        math.cos(phi),
        math.sin(phi),
        math.cos(th),
        math.sin(th),
        math.cos(psi),
        math.sin(psi),
    )
    u, w_, x = v
    return [
        cpsi * cth * u + (cpsi * sth * sphi - spsi * cphi) * w_ + (spsi * sphi + cpsi * cphi * sth) * x,
        spsi * cth * u + (cpsi * cphi + sphi * sth * spsi) * w_ + (sth * spsi * cphi - cpsi * sphi) * x,
        -sth * u + cth * sphi * w_ + cth * cphi * x,
    ]


def _quantized_attitude(roll: float, pitch: float, yaw: float) -> tuple[int, int, int, float, float, float]:
    """The variable leader's heading, pitch and roll [0.01 deg], and the angles
    they stand for [rad]: the device's internal pitch sensor reads a tilt, so
    the leader carries atan(tan(pitch) / cos(roll)), which the transform (and
    the driver) turn back into the pitch."""
    h = round(math.degrees(yaw % (2 * math.pi)) * 100) % 36000
    r = round(math.degrees(roll) * 100)
    tilt = math.atan(math.tan(pitch) / math.cos(roll))
    p = round(math.degrees(tilt) * 100)
    r_rad = math.radians(r / 100)
    p_rad = math.atan(math.tan(math.radians(p / 100)) * math.cos(r_rad))
    return h, p, r, math.radians(h / 100), p_rad, r_rad


class Pd0Encoder:
    """Ensembles of one simulated DVL; numbers them from 1 (24 bits, as RDI)."""

    def __init__(self, cfg: Pd0Config | None = None) -> None:
        self.cfg = cfg or Pd0Config()
        if self.cfg.frame not in FRAMES:
            raise ValueError(f"PD0 frame {self.cfg.frame!r}: one of {', '.join(FRAMES)}")
        if not 0 <= self.cfg.n_cells <= 255:
            raise ValueError("PD0 cells: 0..255 (the fixed leader's byte)")
        self.number = 0

    # ---- a velocity of the vehicle (body axes) as PD0 writes it
    def _frame_values(self, v_body: Sequence[float], att: tuple[float, float, float]) -> list[int]:
        """Four raw values [mm/s] in the configured frame: the bottom's (or
        water's) velocity relative to the DVL, i.e. minus the vehicle's."""
        h, p, r = att
        c = self.cfg
        if c.frame == "earth":
            n, e, d = body_to_ned(r, p, h, v_body)  # the vehicle's velocity over the ground
            vals = [-e, -n, d]  # the bottom's, east north up
        else:
            ship = [-v_body[1], -v_body[0], v_body[2]]  # X stbd, Y fwd, Z up
            if c.frame == "ship" and c.tilts_used:
                # levelled: the ship axes turned by pitch and roll, as the device does
                vals = _mul(_attitude_matrix(0.0, p, r), ship)
            elif c.frame == "beam":
                return self._beam_values(ship)
            else:
                vals = ship
        return [_mm(x) for x in vals] + [0]

    def _beam_values(self, inst: Sequence[float]) -> list[int]:
        """Along each beam, positive toward the transducer (convex, down)."""
        s, co = math.sin(math.radians(self.cfg.beam_angle_deg)), math.cos(math.radians(self.cfg.beam_angle_deg))
        beams = ((-s, 0.0, -co), (s, 0.0, -co), (0.0, s, -co), (0.0, -s, -co))
        return [_mm(-(inst[0] * b[0] + inst[1] * b[1] + inst[2] * b[2])) for b in beams]

    def ensemble(
        self,
        m,
        roll: float,
        pitch: float,
        yaw: float,
        t: float,
        *,
        water_velocity_body: Sequence[float] | None = None,
        depth_m: float = 0.0,
        temperature_c: float = 10.0,
        number: int | None = None,
    ) -> bytes:
        """One ensemble of the measurement ``m`` (a ``dvl_t``: mode, body
        velocity, beam ranges in the simulator's order) at attitude roll,
        pitch, yaw [rad] and time t [s]. The profile's cells carry
        ``water_velocity_body`` (the vehicle's velocity through the water) when
        given, the measured velocity in water-track mode, else bad values."""
        from auv import dvl_t  # the generated types: imported where used

        c = self.cfg
        self.number = (self.number + 1) & 0xFFFFFF if number is None else number & 0xFFFFFF
        h100, p100, r100, h, p, r = _quantized_attitude(roll, pitch, yaw)
        att = (h, p, r)
        bottom = m.mode == dvl_t.MODE_BOTTOM_LOCK
        bt = self._frame_values(m.velocity_mps, att) if bottom else [INVALID] * 4
        if water_velocity_body is not None:
            cell = self._frame_values(water_velocity_body, att)
        elif m.mode == dvl_t.MODE_WATER_TRACK:
            cell = self._frame_values(m.velocity_mps, att)
        else:
            cell = [INVALID] * 4
        ranges = [m.beam_range_m[i] for i in SIM_INDEX_OF_BEAM]
        types = [
            self._fixed_leader(),
            self._variable_leader(t, h100, p100, r100, depth_m, temperature_c),
            struct.pack("<H", 0x0100) + struct.pack(f"<{4 * c.n_cells}h", *(cell * c.n_cells)),
            self._bytes(0x0200, [120 if v != INVALID else 0 for v in cell]),
            self._bytes(0x0300, [80, 81, 82, 83]),
            self._bytes(0x0400, [100 if v != INVALID else 0 for v in cell]),
            self._bottom_track(bt, ranges),
        ]
        return assemble(types)

    def _bytes(self, ident: int, per_cell: Sequence[int]) -> bytes:
        return struct.pack("<H", ident) + bytes(list(per_cell) * self.cfg.n_cells)

    def _fixed_leader(self) -> bytes:
        c = self.cfg
        angle_code = {15.0: 0, 20.0: 1, 30.0: 2}.get(float(c.beam_angle_deg), 3)
        # 600 kHz (011), convex (bit 3), sensor config 1 (bits 4-5), head attached (bit 6), down (bit 7 clear)
        config = 0x03 | 0x08 | 0x10 | 0x40 | (0x40 | angle_code) << 8  # MSB: 4-beam Janus, beam angle
        ex = FRAMES[c.frame] << 3 | (4 if c.tilts_used else 0) | (2 if c.three_beam else 0) | 1
        bin1_cm = round((c.blank_m + c.cell_size_m / 2) * 100)
        return struct.pack(
            "<HBBHBBBBHHHBBBBHBBBBhhBBHHBBBBH8sHBBIB",
            0x0000,
            *FIRMWARE,
            config,
            1,  # simulated data (0: real)
            13,  # lag length
            4,
            c.n_cells,
            1,  # pings per ensemble
            round(c.cell_size_m * 100),
            round(c.blank_m * 100),
            1,  # profiling mode
            64,  # low correlation threshold
            5,  # code repetitions
            0,  # percent good minimum
            2000,  # error velocity maximum [mm/s]
            0,  # time per ping: minutes, seconds, hundredths (0.2 s)
            0,
            20,
            ex,
            0,  # heading alignment EA
            0,  # heading bias EB
            0x7D,  # sensor source: sound speed computed, depth, heading, pitch, roll, temperature
            0x3D,  # sensors available
            bin1_cm,
            round(c.cell_size_m * 100),  # transmit pulse length
            1,  # reference layer: first and last cell
            5,
            50,  # false target threshold
            0,
            0,  # transmit lag distance
            b"\0" * 8,  # CPU board serial number
            0,  # bandwidth
            255,  # power
            0,
            c.serial_number,
            round(c.beam_angle_deg),
        )

    def _variable_leader(self, t: float, h: int, p: int, r: int, depth_m: float, temperature_c: float) -> bytes:
        c = self.cfg
        when = dt.datetime.fromtimestamp(t, dt.timezone.utc) if t > 1e9 else RTC_EPOCH + dt.timedelta(seconds=t)
        rtc = (when.month, when.day, when.hour, when.minute, when.second, when.microsecond // 10000)
        return struct.pack(
            "<HHB6BBHHHHhhHh3B3B8BIHIIBBB6B",
            0x0080,
            self.number & 0xFFFF,
            when.year % 100,
            *rtc,
            self.number >> 16,
            0,  # built-in test result
            c.sound_speed_mps,
            max(0, min(65535, round(depth_m * 10))),
            h,
            p,
            r,
            c.salinity_ppt,
            round(temperature_c * 100),
            0,  # minimum pre-ping wait
            0,
            0,
            0,  # heading, pitch, roll standard deviations
            0,
            0,
            *([0] * 8),  # ADC channels
            0,  # error status word
            0,
            0,  # pressure, variance
            0,
            0,
            when.year // 100,  # the Y2K clock
            when.year % 100,
            *rtc,
        )

    def _bottom_track(self, vel: Sequence[int], ranges_m: Sequence[float]) -> bytes:
        # BT range is RDI's vertical range: the slant range x cos(beam angle), with
        # no pitch or roll in it (the manuals' definition; the driver undoes it)
        cos_beam = math.cos(math.radians(self.cfg.beam_angle_deg))
        cm = [round(x * cos_beam * 100) if x > 0 else 0 for x in ranges_m]
        cm = [min(x, 0xFFFFFF) for x in cm]
        good = vel[0] != INVALID
        return struct.pack(
            "<HHHBBBBH4s4H4h4B4B4BHHH4h4B4B4BH4BB4B4s",
            0x0600,
            1,  # pings per ensemble
            0,  # delay before reacquire
            220,  # correlation minimum
            30,  # evaluation amplitude minimum
            0,  # percent good minimum
            5,  # mode
            1000,  # error velocity maximum
            b"\0" * 4,
            *[x & 0xFFFF for x in cm],
            *vel,
            *([250 if good else 0] * 4),  # correlation
            *([100 if good else 0] * 4),  # evaluation amplitude
            *([100 if good else 0] * 4),  # percent good
            20,  # reference layer: min, near, far [dm]
            20,
            100,
            *([INVALID] * 4),  # reference layer velocity: not measured here
            *([0] * 12),
            2000,  # maximum depth [dm]
            *([100] * 4),  # RSSI
            1,  # gain
            *[x >> 16 for x in cm],  # range MSBs
            b"\0" * 4,
        )


def _mm(v: float) -> int:
    """m/s to the raw mm/s, clipped inside the valid range."""
    return max(-32767, min(32767, round(v * 1000)))


def assemble(types: Sequence[bytes], second: int = 0x7F) -> bytes:
    """The header, the data types and the checksum; ``second`` 0x79 makes a
    Workhorse's waves packet, framed the same way."""
    header_len = 6 + 2 * len(types)
    offsets, at = [], header_len
    for t in types:
        offsets.append(at)
        at += len(t)
    body = struct.pack("<BBHBB", 0x7F, second, at, 0, len(types)) + struct.pack(f"<{len(types)}H", *offsets)
    body += b"".join(types)
    return body + struct.pack("<H", sum(body) & 0xFFFF)


def split(ensemble: bytes) -> list[bytes]:
    """The data types of one ensemble (assemble's inverse), each from its ID."""
    nbytes, n = struct.unpack_from("<H", ensemble, 2)[0], ensemble[5]
    offsets = list(struct.unpack_from(f"<{n}H", ensemble, 6)) + [nbytes]
    return [ensemble[offsets[i] : offsets[i + 1]] for i in range(n)]


class Pd0Dvl:
    """The emulator's side: a ``Dvl`` measurement and the truth it came from
    as the bytes a real unit would send."""

    def __init__(self, cfg: Pd0Config | None = None) -> None:
        self.encoder = Pd0Encoder(cfg)

    def bytes_for(self, m, tr) -> bytes:
        from sim.sensors.instruments import Dvl

        _, _, _, phi, th, psi = tr.eta
        return self.encoder.ensemble(
            m,
            phi,
            th,
            psi,
            tr.t,
            water_velocity_body=Dvl._water_relative(tr),
            depth_m=tr.pressure_depth,
        )

"""The Iver3 frontseat at the wire: its Remote Helm sentences, bytes in and bytes out.

The frontseat's side of the protocol auv-frontseat speaks (c/frontseat/iver3.c;
docs/frontseat.md, "Iver3", which names the public sources of every field):

    backseat -> frontseat  $OSD,...                 answered with $OSI and $C
                           $OMS,HDG,DEPTH,PITCH,KN,T a request: heading [deg], depth
                                                     (m from helm version 5, ft before),
                                                     max pitch [deg], speed [kn], for T s
    frontseat -> backseat  $OSI,...                 mode, position, speed, error, ...
                           $C<h>P<p>R<r>T<t>D<ft>   attitude and depth

This module is the protocol alone (I/O-free, no physics), behind the plug every
frontseat protocol is (sim.devices.frontseat_wire): the emulator keeps the newest
request and answers a data request with what sim.frontseat (the vehicle behind it:
its own loops, its mission, the control rules, the faults) tells it the vehicle is
doing (`report`: mode A while the backseat flies it, M manual, S stopped with the
abort's error word, else N). It acknowledges nothing: a request the vehicle does not
fly (at the surface, during an abort) is simply not flown. A device no sensor polls:
the simulator adds it (Simulator.devices.add) from the `frontseat:` section.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from confcheck import setting
from sim.devices.emulator import DeviceContext
from sim.devices.frontseat_wire import MANUAL, PAYLOAD, STOPPED, FrontseatProtocol, Request, compose

__all__ = ["FT", "KN", "Iver3Frontseat", "Iver3Options", "compose"]

FT = 0.3048
KN = 1852.0 / 3600.0
MODES = {PAYLOAD: "A", MANUAL: "M", STOPPED: "S"}  # else N: its own mission


@dataclass
class Iver3Options:
    # the Remote Helm's major version: $OMS depths in metres from 5, in feet before
    # (Goby3's iver_driver_config.proto); auv-frontseat's --helm-version must match
    helm_version: int = setting(5, ge=1, le=99)


class Iver3Frontseat(FrontseatProtocol):
    protocol = "iver3"
    Options = Iver3Options
    options: Iver3Options

    def __init__(self, ctx: DeviceContext) -> None:
        super().__init__(ctx)
        self.polls = 0

    def sentence(self, fields: list[str], t: float) -> None:
        if fields[0] == "OSD":
            self.polls += 1
            self._answer(t)
        elif fields[0] == "OMS":
            self._oms(fields, t)
        else:
            self._refuse("unknown sentence")

    def _oms(self, f: list[str], t: float) -> None:
        try:
            hdg, depth, pitch, kn, timeout = (float(x) for x in f[1:6])
        except ValueError:
            self._refuse("bad $OMS")
            return
        if len(f) != 6 or not all(math.isfinite(x) for x in (hdg, depth, pitch, kn, timeout)):
            self._refuse("bad $OMS")
            return
        if not (0.0 <= hdg < 360.0 and depth >= 0.0 and 0.0 < pitch <= 90.0 and kn >= 0.0 and timeout > 0.0):
            self._refuse("$OMS out of range")
            return
        depth_m = depth if self.options.helm_version >= 5 else depth * FT
        self.request = Request(t, math.radians(hdg), depth_m, kn * KN, timeout, max_pitch_rad=math.radians(pitch))
        self.requests += 1

    def _answer(self, t: float) -> None:
        tr = self.truth
        if tr is None:
            return
        hdg = math.degrees(tr.eta[5]) % 360.0
        vn, ve, _ = tr.velocity_ned()
        sog_kn = math.hypot(vn, ve) / KN
        mode = MODES.get(self.report.helm, "N")
        error = self.report.error or "N"
        # Goby3's field order: fins and motor (hex), mode, next waypoint, latitude,
        # longitude, speed [kn], distance to the next waypoint, error, altimeter [ft],
        # park time, magnetic declination, mission, time remaining, true heading, depth [ft]
        osi = (
            f"OSI,8080808080,{mode},0,{tr.latitude_deg:.7f},{tr.longitude_deg:.7f},{sog_kn:.2f},0.0,"
            f"{error},{tr.altitude_m / FT:.1f},P0,0.0,sim,0.0,{hdg:.1f},{tr.eta[2] / FT:.2f}"
        )
        compass = f"C{hdg:.1f}P{math.degrees(tr.eta[4]):.1f}R{math.degrees(tr.eta[3]):.1f}T15.0D{tr.eta[2] / FT:.2f}"
        self.send(compose(compass) + compose(osi), t)

"""The vehicle's pilot, flown in-process: the pilot plugin's C loops through ctypes.

The vehicle's pilot is a CHASM manager running missions/pilot/pilot.chasm
with the pilot plugin (c/plugins/pilot). The validation report and tests
that fly the physics in-process (no LCM, no clock) need the same controller,
so they run the same code: the plugin's loops (c/plugins/pilot/pilot_loops.c)
are also built as build/lib/libauvpilot.so (c/pilotlib, `make build`), wired
as the plan's `fly` state wires them (heading_control on the rudder,
depth_control or pitch_control on the stern plane, speed_control or
rpm_control on the prop). There is no Python copy of the law.

Nor of the gains: the library names every gain it needs after the plan's
`param` (heading_kp, ...), and Pilot reads each from the plan's `param`
lines, the one place they are set; a plan missing one is an error.
tests/plugins/test_pilot_law.py holds the library to the plugin run by
libchasm on the same inputs.
"""

from __future__ import annotations

import ctypes
import functools
import math
import re
from pathlib import Path

from auvlcm.paths import ROOT, build_dir

LIBRARY = "libauvpilot.so"
PLAN = ROOT / "missions" / "pilot" / "pilot.chasm"
# The units the plan's gains are written in, to SI (the plan loader's own
# conversions for these; a gain in another unit is reported as missing).
_UNITS = {"": 1.0, "rad": 1.0, "deg": math.pi / 180.0, "deg/s": math.pi / 180.0, "rad/s": 1.0}
_UNITS.update({"s": 1.0, "m": 1.0, "m/s": 1.0})
_PARAM = re.compile(r"^param\s+(\w+)\s*=\s*([-+0-9.eE]+)\s*([a-z/]*)")


class PilotUnavailable(RuntimeError):
    """The pilot library is not built."""


def library_path() -> Path:
    return build_dir() / "lib" / LIBRARY


@functools.cache
def _library() -> ctypes.PyDLL:
    """The pilot library, loaded once (PyDLL: a call is far cheaper than
    releasing the GIL, as in sim.dynamics)."""
    path = library_path()
    if not path.exists():
        raise PilotUnavailable(f"{path} is not built: run `make build` (the pilot's loops are C, c/pilotlib/)")
    lib = ctypes.PyDLL(str(path))
    p, d = ctypes.c_void_p, ctypes.c_double
    for name, args, res in (
        ("auv_pilot_size", [], ctypes.c_size_t),
        ("auv_pilot_init", [p], None),
        ("auv_pilot_gain_count", [], ctypes.c_size_t),
        ("auv_pilot_gain_name", [ctypes.c_size_t], ctypes.c_char_p),
        ("auv_pilot_set_gain", [p, ctypes.c_char_p, d], ctypes.c_int),
        ("auv_pilot_gain", [p, ctypes.c_char_p], d),
        ("auv_pilot_start_heading", [p, d], None),
        ("auv_pilot_start_vertical", [p, d, d], None),
        ("auv_pilot_start_prop", [p, d], None),
        ("auv_pilot_rudder", [p, d, d, d, d], d),
        ("auv_pilot_plane_for_depth", [p, d, d, d, d, d], d),
        ("auv_pilot_plane_for_pitch", [p, d, d, d, d], d),
        ("auv_pilot_prop_for_speed", [p, d, d, ctypes.c_int, d], d),
        ("auv_pilot_prop_for_rpm", [p, d, d], d),
    ):
        fn = getattr(lib, name)
        fn.argtypes, fn.restype = args, res
    return lib


def gain_names() -> list[str]:
    """Every gain the library takes, named as the plan's `param`s."""
    lib = _library()
    return [lib.auv_pilot_gain_name(i).decode() for i in range(lib.auv_pilot_gain_count())]


def plan_gains(path: Path = PLAN) -> dict[str, float]:
    """The gains the pilot plan sets (SI), each gain the library takes; a
    ValueError names any the plan does not set."""
    values: dict[str, float] = {}
    for line in path.read_text().splitlines():
        m = _PARAM.match(line.strip())
        if m and m.group(3) in _UNITS:
            values[m.group(1)] = float(m.group(2)) * _UNITS[m.group(3)]
    names = gain_names()
    missing = [n for n in names if n not in values]
    if missing:
        raise ValueError(f"{path}: the pilot plan sets no {', '.join(missing)}")
    return {n: values[n] for n in names}


class Pilot:
    """Heading, depth (or pitch) and speed (or rpm) control, one call per cycle
    of `dt` seconds (the attribute may change between calls)."""

    def __init__(self, gains: dict[str, float] | None = None, dt: float = 0.05) -> None:
        lib = self._lib = _library()
        self.gains = plan_gains() if gains is None else dict(gains)
        self.dt = dt
        self._buf = (ctypes.c_double * (lib.auv_pilot_size() // 8 + 1))()
        self._p = ctypes.cast(self._buf, ctypes.c_void_p)
        lib.auv_pilot_init(self._p)
        for name, value in self.gains.items():
            if lib.auv_pilot_set_gain(self._p, name.encode(), float(value)) != 0:
                raise ValueError(f"the pilot has no gain {name!r}")

    def start(self, pitch: float, plane: float = 0.0, rpm: float = 0.0, rudder: float = 0.0) -> None:
        """Take over without a jump, as the behaviors' start() does."""
        self.start_heading(rudder)
        self.start_vertical(pitch, plane)
        self.start_prop(rpm)

    def start_heading(self, rudder: float) -> None:
        self._lib.auv_pilot_start_heading(self._p, rudder)

    def start_vertical(self, pitch: float, plane: float) -> None:
        """Restart the stern plane's loops (when changing between depth and pitch)."""
        self._lib.auv_pilot_start_vertical(self._p, pitch, plane)

    def start_prop(self, rpm: float) -> None:
        self._lib.auv_pilot_start_prop(self._p, rpm)

    def rudder(self, heading_cmd: float, heading: float, r: float) -> float:
        return self._lib.auv_pilot_rudder(self._p, heading_cmd, heading, r, self.dt)

    def stern_for_pitch(self, pitch_cmd: float, pitch: float, q: float) -> float:
        return self._lib.auv_pilot_plane_for_pitch(self._p, pitch_cmd, pitch, q, self.dt)

    def stern_for_depth(self, target: float, depth: float, pitch: float, q: float) -> float:
        return self._lib.auv_pilot_plane_for_depth(self._p, target, depth, pitch, q, self.dt)

    def prop(self, speed_cmd: float, u: float, through_water: bool = False) -> float:
        """rpm for speed_cmd; through the water: the rpm law alone (setpoint_t)."""
        return self._lib.auv_pilot_prop_for_speed(self._p, speed_cmd, u, int(through_water), self.dt)

    def prop_rpm(self, rpm_cmd: float) -> float:
        return self._lib.auv_pilot_prop_for_rpm(self._p, rpm_cmd, self.dt)

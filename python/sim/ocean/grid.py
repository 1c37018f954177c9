"""The ocean's fields from gridded ocean-model output: NetCDF with CF conventions.

Read with xarray (engine netCDF4) once, checked whole, converted to what the
world holds (in-situ temperature [degC], practical salinity [PSU]) on a
rectilinear grid in the world's frame (time [s of sim time], depth [m, down],
north [m], east [m]), and interpolated linearly in all four.

What a file must be (each breach is an OceanError naming the file and what is
wrong, so the configuration's check reports it before anything starts):

- NetCDF (classic or NetCDF-4/HDF5);
- a temperature variable found by its CF `standard_name`:
  `sea_water_temperature` (in-situ), `sea_water_potential_temperature` or
  `sea_water_conservative_temperature` (converted by TEOS-10), with CF `units`
  (degC or K);
- a salinity variable: `sea_water_salinity` or `sea_water_practical_salinity`
  (units 1, psu, 1e-3) or `sea_water_absolute_salinity` (g/kg);
- both on the dimensions (time, depth, y, x) in CF's order T, Z, Y, X (time
  may be absent: a static field), each with a 1-D coordinate variable
  with units: time `<unit> since <date>`, depth in metres (`positive: up`
  read as heights), y and x either latitude / longitude (degrees_north /
  degrees_east, converted about the world origin) or north / east in metres;
  at least 2 depths, 2 ys and 2 xs; every coordinate strictly monotonic;
- no missing value (NaN or _FillValue) anywhere: land must be cut away or
  filled before the file is used;
- values a sea can hold (-3..45 degC, 0..45 PSU), which catches wrong units.

Above the shallowest level the field is that level's (the mixed layer);
outside the grid horizontally, below its deepest level or past its times it
is held at the edge: the configuration's check refuses a grid that does not
cover the world's area (`coverage_problem`).
"""

from __future__ import annotations

import hashlib
import math
import re
from datetime import datetime
from pathlib import Path

import numpy as np

import sim.ocean.teos10 as teos10

HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
TEMPERATURE_NAMES = {
    "sea_water_temperature": "in-situ",
    "sea_water_potential_temperature": "potential",
    "sea_water_conservative_temperature": "conservative",
}
SALINITY_NAMES = {
    "sea_water_salinity": "practical",
    "sea_water_practical_salinity": "practical",
    "sea_water_absolute_salinity": "absolute",
}
CELSIUS = {"degc", "degree_c", "degrees_c", "degree_celsius", "degrees_celsius", "celsius", "deg_c", "°c"}
KELVIN = {"k", "kelvin", "degk", "degree_kelvin", "degrees_kelvin"}
PRACTICAL_UNITS = {"1", "psu", "pss-78", "pss78", "1e-3", "0.001", "10-3", "1.0", "practical_salinity_unit"}
ABSOLUTE_UNITS = {"g/kg", "g kg-1", "g kg^-1", "g.kg-1", "g kg**-1"}
METRES = {"m", "metre", "metres", "meter", "meters"}
DEG_NORTH = {"degrees_north", "degree_north", "degree_n", "degrees_n", "degreen", "degreesn"}
DEG_EAST = {"degrees_east", "degree_east", "degree_e", "degrees_e", "degreee", "degreese"}
TIME_UNIT_S = {
    "seconds": 1.0,
    "second": 1.0,
    "secs": 1.0,
    "sec": 1.0,
    "s": 1.0,
    "minutes": 60.0,
    "minute": 60.0,
    "mins": 60.0,
    "min": 60.0,
    "hours": 3600.0,
    "hour": 3600.0,
    "hrs": 3600.0,
    "hr": 3600.0,
    "h": 3600.0,
    "days": 86400.0,
    "day": 86400.0,
    "d": 86400.0,
}
T_RANGE_C = (-3.0, 45.0)
S_RANGE_PSU = (0.0, 45.0)
ORDER = ("time", "depth", "y", "x")


class OceanError(ValueError):
    """A grid file or an ocean parameter that cannot make an ocean; its text names the file."""


def _attr(var, name: str) -> str:
    v = var.attrs.get(name, "")
    return v.strip() if isinstance(v, str) else str(v)


def _describe(ds) -> str:
    out = []
    for name, var in ds.data_vars.items():
        sn = _attr(var, "standard_name")
        out.append(f"{name} ({sn})" if sn else f"{name} (no standard_name)")
    return ", ".join(out) or "no data variables"


class OceanGrid:
    """Temperature and salinity of a NetCDF file, in the world's frame."""

    def __init__(self, path: Path, lat0: float, lon0: float, start: str = "") -> None:
        self.path = path
        self.lat0, self.lon0 = lat0, lon0
        try:
            raw = path.read_bytes()
        except OSError as exc:
            raise OceanError(f"{path}: cannot read the ocean grid ({exc.strerror})") from None
        if not (raw[:3] == b"CDF" or raw[:8] == HDF5_SIGNATURE):
            raise OceanError(f"{path}: not a NetCDF file (it starts with neither 'CDF' nor the HDF5 signature)")
        self.sha256 = hashlib.sha256(raw).hexdigest()
        import xarray as xr  # a second of imports: only for worlds with a grid

        try:
            ds = xr.open_dataset(path, engine="netcdf4", decode_times=False, mask_and_scale=True)
        except Exception as exc:  # noqa: BLE001 - netCDF4 raises OSError, ValueError, RuntimeError
            raise OceanError(f"{path}: not a readable NetCDF file ({exc})") from None
        try:
            with ds:
                self._read(ds, start)
        except OceanError:
            raise
        except (KeyError, ValueError, TypeError) as exc:
            raise OceanError(f"{path}: cannot read the ocean grid ({exc})") from None

    # ------------------------------------------------------------ reading
    def _err(self, msg: str) -> OceanError:
        return OceanError(f"{self.path}: {msg}")

    def _find(self, ds, names: dict[str, str], what: str):
        for sn in names:
            for name, var in ds.data_vars.items():
                if _attr(var, "standard_name") == sn:
                    return name, var, names[sn]
        raise self._err(
            f"no {what} variable: CF needs one with standard_name {' or '.join(names)}; the file has {_describe(ds)}"
        )

    def _read(self, ds, start: str) -> None:
        tname, tvar, tkind = self._find(ds, TEMPERATURE_NAMES, "temperature")
        sname, svar, skind = self._find(ds, SALINITY_NAMES, "salinity")
        tunits = _attr(tvar, "units")
        if not tunits:
            raise self._err(f"variable '{tname}' has no units attribute (CF: degC or K)")
        if tunits.lower() not in CELSIUS | KELVIN:
            raise self._err(f"variable '{tname}' has units {tunits!r}: not a temperature (CF: degC or K)")
        sunits = _attr(svar, "units")
        want = ABSOLUTE_UNITS if skind == "absolute" else PRACTICAL_UNITS
        hint = "g/kg" if skind == "absolute" else "1, psu or 1e-3"
        if not sunits:
            raise self._err(f"variable '{sname}' has no units attribute (CF: {hint})")
        if sunits.lower() not in want:
            raise self._err(f"variable '{sname}' has units {sunits!r}: not a {skind} salinity (CF: {hint})")
        if tuple(tvar.dims) != tuple(svar.dims):
            raise self._err(
                f"'{tname}' is on dimensions ({', '.join(tvar.dims)}), '{sname}' on ({', '.join(svar.dims)}): "
                "they must share one grid"
            )
        kinds = [self._axis_kind(ds, dim) for dim in tvar.dims]
        names = [k for k, _ in kinds]
        want_order = list(ORDER) if "time" in names else list(ORDER[1:])
        if sorted(names) != sorted(want_order) or len(set(names)) != len(names):
            missing = [k for k in ORDER[1:] if k not in names]
            raise self._err(
                f"'{tname}' is on dimensions ({', '.join(tvar.dims)}): "
                + (f"no {' or '.join(missing)} dimension; " if missing else "")
                + "expected (time, depth, y, x): CF's T, Z, Y, X (time may be left out)"
            )
        if names != want_order:
            got = ", ".join(f"{d} ({k})" for d, k in zip(tvar.dims, names))
            raise self._err(
                f"'{tname}' has its dimensions in the order {got}: expected "
                f"({', '.join(want_order)}), CF's T, Z, Y, X; reorder the file (e.g. ncpdq -a)"
            )
        axes = dict(zip(names, (info for _, info in kinds)))
        horizontal = {axes["y"]["unit"], axes["x"]["unit"]}
        if horizontal not in ({"lat", "lon"}, {"m"}):
            raise self._err(
                "its y and x must be latitude and longitude (degrees_north, degrees_east) "
                f"or north and east in metres; they are {axes['y']['unit']} and {axes['x']['unit']}"
            )
        t_raw = np.asarray(tvar.values, float)
        s_raw = np.asarray(svar.values, float)
        if "time" not in names:
            t_raw, s_raw = t_raw[None], s_raw[None]
            time_s = np.array([0.0])
            self.static = True
        else:
            time_s = self._times(axes["time"], start)
            self.static = time_s.size == 1
        for name, raw in ((tname, t_raw), (sname, s_raw)):
            bad = ~np.isfinite(raw)
            if bad.any():
                first = np.unravel_index(int(np.argmax(bad)), bad.shape)
                where = ", ".join(f"{d}={i}" for d, i in zip(ORDER, first))
                raise self._err(
                    f"variable '{name}' has {int(bad.sum())} missing values (NaN or _FillValue), "
                    f"the first at index {where}: every point of the grid must be water (cut land away or fill it)"
                )
        depth = self._depths(axes["depth"])
        ys, xs = axes["y"]["values"], axes["x"]["values"]
        self._monotonic(axes["y"]["name"], ys, 2)
        self._monotonic(axes["x"]["name"], xs, 2)
        if axes["y"]["unit"] == "lat":
            from sim.geo import LocalFrame

            frame = LocalFrame(self.lat0, self.lon0)
            north = np.array([frame.to_ned(v, self.lon0)[0] for v in ys])
            east = np.array([frame.to_ned(self.lat0, v)[1] for v in xs])
            lat = ys[None, None, :, None]
            lon = xs[None, None, None, :]
        else:
            north, east = ys, xs
            lat, lon = self.lat0, self.lon0
        # every axis ascending: flip the descending ones
        axes_vals = [time_s, depth, north, east]
        for i, vals in enumerate(axes_vals):
            if vals.size > 1 and vals[1] < vals[0]:
                axes_vals[i] = vals[::-1]
                t_raw = np.flip(t_raw, axis=i)
                s_raw = np.flip(s_raw, axis=i)
                if i == 2 and not np.isscalar(lat):
                    lat = np.flip(lat, axis=2)
                if i == 3 and not np.isscalar(lon):
                    lon = np.flip(lon, axis=3)
        time_s, depth, north, east = axes_vals
        p = teos10.pressure_dbar(depth, self.lat0)[None, :, None, None]
        if tunits.lower() in KELVIN:
            t_raw = t_raw - 273.15
        if skind == "absolute":
            sa = s_raw
            sp = teos10.practical_from_absolute(sa, p, lon, lat)
        else:
            sp = s_raw
            sa = teos10.absolute_from_practical(sp, p, lon, lat) if tkind != "in-situ" else None
        if tkind == "potential":
            t = teos10.in_situ_from_potential(sa, t_raw, p)
        elif tkind == "conservative":
            t = teos10.in_situ_from_conservative(sa, t_raw, p)
        else:
            t = t_raw
        t = np.broadcast_to(t, t_raw.shape)
        sp = np.broadcast_to(sp, s_raw.shape)
        for name, vals, (lo, hi), unit in ((tname, t, T_RANGE_C, "degC"), (sname, sp, S_RANGE_PSU, "PSU")):
            vmin, vmax = float(np.min(vals)), float(np.max(vals))
            if not (math.isfinite(vmin) and math.isfinite(vmax)) or vmin < lo or vmax > hi:
                raise self._err(
                    f"variable '{name}' spans {vmin:g} to {vmax:g} {unit}, beyond what a sea holds "
                    f"({lo:g} to {hi:g}): wrong units?"
                )
        self.time_s, self.depth_m, self.north_m, self.east_m = time_s, depth, north, east
        self._ts = np.ascontiguousarray(np.stack([t, sp], axis=-1), dtype=float)

    def _axis_kind(self, ds, dim: str) -> tuple[str, dict]:
        """What a dimension is ("time", "depth", "y", "x") and its coordinate values."""
        if dim not in ds.variables:
            raise self._err(f"dimension '{dim}' has no coordinate variable (CF: a 1-D variable of the same name)")
        var = ds[dim]
        if var.ndim != 1:
            raise self._err(f"coordinate '{dim}' is not 1-D")
        axis = _attr(var, "axis").upper()
        sn = _attr(var, "standard_name").lower()
        units = _attr(var, "units")
        u = units.lower()
        name = dim.lower()
        values = np.asarray(var.values, float)
        if values.size and not np.all(np.isfinite(values)):
            raise self._err(f"coordinate '{dim}' has missing values")
        info = {"name": dim, "units": units, "values": values, "attrs": dict(var.attrs)}
        if axis == "T" or sn == "time" or " since " in u or name in ("time", "t"):
            return "time", info
        if axis == "Z" or sn in ("depth", "height", "altitude") or name in ("depth", "z", "deptht", "lev", "level"):
            return "depth", info
        if sn == "latitude" or u in DEG_NORTH or name in ("lat", "latitude"):
            info["unit"] = "lat"
            return "y", info
        if sn == "longitude" or u in DEG_EAST or name in ("lon", "longitude"):
            info["unit"] = "lon"
            return "x", info
        if axis == "Y" or sn == "projection_y_coordinate" or name in ("north", "north_m", "y"):
            info["unit"] = self._metres(dim, units)
            return "y", info
        if axis == "X" or sn == "projection_x_coordinate" or name in ("east", "east_m", "x"):
            info["unit"] = self._metres(dim, units)
            return "x", info
        raise self._err(
            f"cannot tell what dimension '{dim}' is: give its coordinate a CF standard_name "
            "(time, depth, latitude, longitude, projection_y_coordinate, projection_x_coordinate) or axis (T, Z, Y, X)"
        )

    def _metres(self, dim: str, units: str) -> str:
        if not units:
            raise self._err(f"coordinate '{dim}' has no units attribute (CF: m)")
        if units.lower() not in METRES:
            raise self._err(
                f"coordinate '{dim}' has units {units!r}: expected metres (or latitude/longitude in degrees)"
            )
        return "m"

    def _monotonic(self, dim: str, values: np.ndarray, least: int) -> None:
        if values.size < least:
            raise self._err(f"coordinate '{dim}' has {values.size} value(s): at least {least} are needed")
        if values.size > 1:
            d = np.diff(values)
            if not (np.all(d > 0) or np.all(d < 0)):
                raise self._err(f"coordinate '{dim}' is not strictly increasing or decreasing")

    def _times(self, info: dict, start: str) -> np.ndarray:
        dim, units = info["name"], info["units"]
        if not units:
            raise self._err(f"coordinate '{dim}' has no units attribute (CF: e.g. 'seconds since 2024-06-01')")
        m = re.fullmatch(r"\s*(\w+)\s+since\s+(.+?)\s*", units)
        if not m or m.group(1).lower() not in TIME_UNIT_S:
            raise self._err(
                f"coordinate '{dim}' has units {units!r}: expected CF time units "
                "'<seconds|minutes|hours|days> since <date>'"
            )
        values = info["values"]
        self._monotonic(dim, values, 1)
        if values.size > 1 and values[1] < values[0]:
            raise self._err(f"coordinate '{dim}' runs backwards")
        scale = TIME_UNIT_S[m.group(1).lower()]
        ref = values[0]
        if start:
            import cftime

            calendar = str(info["attrs"].get("calendar", "standard"))
            try:
                when = datetime.fromisoformat(start)
                ref = float(cftime.date2num(when.replace(tzinfo=None), units, calendar))
            except (ValueError, TypeError) as exc:
                raise self._err(f"cannot place grid_start {start!r} on its time axis ({exc})") from None
        return (values - ref) * scale

    def _depths(self, info: dict) -> np.ndarray:
        dim, units = info["name"], info["units"]
        if not units:
            raise self._err(f"coordinate '{dim}' has no units attribute (CF: m)")
        if units.lower() not in METRES:
            raise self._err(f"coordinate '{dim}' has units {units!r}: expected metres")
        values = info["values"]
        self._monotonic(dim, values, 2)
        positive = str(info["attrs"].get("positive", "")).lower()
        sn = str(info["attrs"].get("standard_name", "")).lower()
        if positive == "up" or sn in ("height", "altitude"):
            values = -values
        return values

    # ------------------------------------------------------------ checks
    def coverage_problem(
        self, north: tuple[float, float], east: tuple[float, float], max_depth: float, duration_s: float
    ) -> str:
        """Why the grid does not cover an area over [0, duration_s] ("" if it does)."""
        n, e, z, t = self.north_m, self.east_m, self.depth_m, self.time_s
        tol = 1e-6
        if north[0] < n[0] - tol or north[1] > n[-1] + tol:
            return (
                f"the grid covers north {n[0]:.1f} to {n[-1]:.1f} m of the world origin, "
                f"the area needs {north[0]:g} to {north[1]:g} m"
            )
        if east[0] < e[0] - tol or east[1] > e[-1] + tol:
            return (
                f"the grid covers east {e[0]:.1f} to {e[-1]:.1f} m of the world origin, "
                f"the area needs {east[0]:g} to {east[1]:g} m"
            )
        if max_depth > z[-1] + tol:
            return f"the grid's deepest level is {z[-1]:g} m, the area needs {max_depth:g} m"
        if not self.static:
            if t[0] > tol:
                return f"the grid's first time is {t[0]:g} s after sim time 0 (grid_start)"
            if duration_s > t[-1] + tol:
                return f"the grid's times end {t[-1]:g} s after sim time 0, the run lasts {duration_s:g} s"
        return ""

    # ------------------------------------------------------------ sampling
    def sample(self, t, north, east, depth) -> tuple[np.ndarray, np.ndarray]:
        """In-situ temperature [degC] and practical salinity [PSU] at points
        (numpy broadcasting), linear in time, depth, north and east; held at the edges."""
        t, north, east, depth = np.broadcast_arrays(
            np.asarray(t, float), np.asarray(north, float), np.asarray(east, float), np.asarray(depth, float)
        )
        idx = [
            _bracket(ax, x)
            for ax, x in zip((self.time_s, self.depth_m, self.north_m, self.east_m), (t, depth, north, east))
        ]
        out = np.zeros(t.shape + (2,))
        ts = self._ts
        for corner in range(16):
            w = np.ones(t.shape)
            sel = []
            for k, (i0, i1, f) in enumerate(idx):
                if corner >> k & 1:
                    w = w * f
                    sel.append(i1)
                else:
                    w = w * (1.0 - f)
                    sel.append(i0)
            out += w[..., None] * ts[sel[0], sel[1], sel[2], sel[3]]
        return out[..., 0], out[..., 1]


def _bracket(axis: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lower and upper index and the fraction between them of x on an ascending axis (clamped)."""
    n = axis.size
    if n == 1:
        z = np.zeros(x.shape, int)
        return z, z, np.zeros(x.shape)
    xc = np.clip(x, axis[0], axis[-1])
    i = np.clip(np.searchsorted(axis, xc, side="right") - 1, 0, n - 2)
    f = (xc - axis[i]) / (axis[i + 1] - axis[i])
    return i, i + 1, f


_CACHE: dict[tuple, OceanGrid] = {}


def load_grid(path: Path, lat0: float, lon0: float, start: str = "") -> OceanGrid:
    """An OceanGrid, read once per file version, origin and start (the
    configuration's check and the simulator's world read the same file)."""
    try:
        st = path.stat()
        key = (str(path.resolve()), st.st_mtime_ns, st.st_size, lat0, lon0, start)
    except OSError:
        key = None
    if key is not None and key in _CACHE:
        return _CACHE[key]
    grid = OceanGrid(path, lat0, lon0, start)
    if key is not None:
        if len(_CACHE) >= 4:
            _CACHE.pop(next(iter(_CACHE)))
        _CACHE[key] = grid
    return grid

"""The ocean's fields (sim.ocean, docs/sampling.md): the analytic front,
thermocline and plumes, their determinism, a gridded NetCDF file read back and
every bad file refused with its name and the problem, TEOS-10 sound speed, and
the acoustic travel times that use it. Pure Python, each test well under a second
or two (xarray writes the small files)."""

from __future__ import annotations

import math
from pathlib import Path

import gsw
import numpy as np
import pytest

from sim.config import ConfigError, loads
from sim.environment import CurrentLayer, Environment, EnvParams, Transponder
from sim.model import Truth
from sim.ocean import Front, Ocean, OceanError, OceanGrid, OceanParams, Plume, Thermocline, WaterMass, teos10
from sim.sensors import Lbl, LblConfig

LAT, LON = 41.52, -70.67


def ocean(seed=1, **front) -> Ocean:
    p = OceanParams(
        front=Front(**{"offset_m": 200.0, "width_m": 10.0, **front}),
        water_a=WaterMass(16.0, 32.5),
        water_b=WaterMass(12.0, 34.5),
        deep=WaterMass(8.0, 35.0),
        thermocline=Thermocline(30.0, 4.0),
    )
    return Ocean(p, seed, LAT, LON)


def front_crossing(o: Ocean, t: float, north: float) -> float:
    """Where the surface temperature is half-way between the two water masses,
    found along an east line (the front runs north: angle 0)."""
    east = np.linspace(-500.0, 1000.0, 15001)
    temp, _ = o.fields(t, north, east, 0.0)
    return float(np.interp(14.0, temp[::-1], east[::-1]))  # 16 west of it, 12 east


# ------------------------------------------------------------ analytic fields
def test_the_front_is_where_its_parameters_put_it_and_moves_with_time():
    o = ocean(amplitude_m=80.0, wavelength_m=1000.0, period_s=600.0)
    for t, north in ((0.0, 0.0), (0.0, 250.0), (150.0, 0.0), (300.0, 700.0)):
        assert front_crossing(o, t, north) == pytest.approx(o.front_position(t, north), abs=0.05)
    # the meander: 2 A from crest to trough along the front, and it travels
    along = np.linspace(0.0, 1000.0, 201)
    xs = [o.front_position(0.0, s) for s in along]
    assert max(xs) - min(xs) == pytest.approx(160.0, abs=0.5)
    assert max(xs) == pytest.approx(280.0, abs=0.5) and min(xs) == pytest.approx(120.0, abs=0.5)
    at_origin = [o.front_position(t, 0.0) for t in np.linspace(0.0, 600.0, 61)]
    assert max(at_origin) - min(at_origin) == pytest.approx(160.0, abs=0.5)  # one period at a point
    assert o.front_position(600.0, 0.0) == pytest.approx(o.front_position(0.0, 0.0))
    # a quarter period later a point a quarter wavelength on sees what the origin saw
    assert o.front_position(150.0, 250.0) == pytest.approx(o.front_position(0.0, 0.0))
    # drift moves the whole front across itself
    d = ocean(drift_mps=0.1)
    assert front_crossing(d, 1000.0, 0.0) - front_crossing(d, 0.0, 0.0) == pytest.approx(100.0, abs=0.05)


def test_the_front_runs_along_its_angle():
    o = ocean(angle_rad=math.pi / 4, offset_m=100.0)
    # right of a front running north-east is south-east: water b there, a north-west
    t_b, s_b = o.temperature_salinity(0.0, -300.0, 300.0, 1.0)
    t_a, s_a = o.temperature_salinity(0.0, 300.0, -300.0, 1.0)
    assert (t_a, s_a) == pytest.approx((16.0, 32.5), abs=1e-3)
    assert (t_b, s_b) == pytest.approx((12.0, 34.5), abs=1e-3)
    # its half-way point is offset_m from the origin, across it
    r = (-math.sin(math.pi / 4), math.cos(math.pi / 4))
    mid, _ = o.temperature_salinity(0.0, 100.0 * r[0], 100.0 * r[1], 1.0)
    assert mid == pytest.approx(14.0, abs=1e-4)


def test_the_thermocline_separates_upper_and_deep_water():
    o = ocean()
    west = (0.0, 0.0, -300.0)  # water a
    temp, salt = o.fields(*west, np.array([0.0, 26.0, 30.0, 34.0, 60.0]))
    assert temp[0] == pytest.approx(16.0, abs=1e-4) and temp[-1] == pytest.approx(8.0, abs=1e-4)
    assert temp[2] == pytest.approx(12.0) and salt[2] == pytest.approx(33.75)  # half-way at its centre
    # one thickness above / below: (1 -+ tanh 1) / 2 of the way
    frac = 0.5 * (1.0 - math.tanh(1.0))
    assert temp[1] == pytest.approx(8.0 + 8.0 * (1.0 - frac))
    assert temp[3] == pytest.approx(8.0 + 8.0 * frac)
    assert np.all(np.diff(temp) < 0) and np.all(np.diff(salt) > 0)


def test_the_fields_are_deterministic_from_the_seed():
    pts = (np.linspace(0, 400, 9), np.linspace(-50, 450, 9), np.linspace(0, 40, 9))
    a = ocean(seed=7, amplitude_m=60.0, period_s=900.0)
    b = ocean(seed=7, amplitude_m=60.0, period_s=900.0)
    c = ocean(seed=8, amplitude_m=60.0, period_s=900.0)
    for t in (0.0, 123.4, 5000.0):
        assert np.array_equal(a.fields(t, *pts)[0], b.fields(t, *pts)[0])
        assert not np.array_equal(a.fields(t, *pts)[0], c.fields(t, *pts)[0])
    # and the world's ocean is the ocean of its parameters (what env_model_t carries)
    env = Environment(EnvParams(seed=7, ocean=a.params))
    assert env.temperature_salinity(10.0, 50.0, 190.0, 3.0) == a.temperature_salinity(10.0, 50.0, 190.0, 3.0)


def test_a_world_without_ocean_keeps_uniform_water_and_its_sound_speed():
    env = Environment(EnvParams(sound_speed_mps=1490.0, sound_speed_gradient_per_m=0.02))
    assert env.ocean is None
    assert env.temperature_salinity(5.0, 1.0, 2.0, 3.0) == (12.0, 35.0)
    assert env.sound_speed(20.0) == 1490.4
    assert env.path_sound_speed(0.0, (0, 0, 10.0), (500.0, 0, 30.0)) == env.mean_sound_speed(10.0, 30.0) == 1490.4


def test_a_plume_is_carried_by_the_current_and_spreads():
    env = Environment(
        EnvParams(
            seed=3,
            current=[CurrentLayer(0.0, 0.2, 0.1), CurrentLayer(40.0, 0.0, 0.0)],
            ocean=OceanParams(
                water_a=WaterMass(14.0, 34.0),
                water_b=WaterMass(14.0, 34.0),
                thermocline=Thermocline(200.0, 5.0),
                plumes=[Plume(100.0, -50.0, 10.0, 60.0, 30.0, 2.0, 0.5, 2.0, -3.0)],
            ),
        )
    )
    o = env.ocean
    assert o.plume_centre(0, 59.0) is None
    assert env.temperature_salinity(59.0, 100.0, -50.0, 10.0) == pytest.approx((14.0, 34.0))
    # released at 60 s at its anomaly; 1000 s later 0.15 / 0.075 m/s (the profile at 10 m) on
    assert env.temperature_salinity(60.0, 100.0, -50.0, 10.0) == pytest.approx((16.0, 31.0))
    n, e, d = o.plume_centre(0, 1060.0)
    assert (n, e, d) == pytest.approx((100.0 + 150.0, -50.0 + 75.0, 10.0))
    var = 30.0**2 + 2 * 0.5 * 1000.0
    peak = 30.0**2 / var
    assert env.temperature_salinity(1060.0, n, e, d) == pytest.approx((14.0 + 2.0 * peak, 34.0 - 3.0 * peak))
    # one sigma off its centre horizontally, and half its thickness below
    sig = math.sqrt(var)
    temp, _ = env.temperature_salinity(1060.0, n + sig, e, d + 1.0)
    assert temp == pytest.approx(14.0 + 2.0 * peak * math.exp(-0.5 - 0.125))
    # where it was released it has gone
    assert env.temperature_salinity(1060.0, 100.0, -50.0, 10.0)[0] < 14.0 + 0.01


def test_the_plume_drift_integrates_the_slow_current_variation_in_closed_form():
    env = Environment(
        EnvParams(
            seed=5,
            current=[CurrentLayer(0.0, 0.1, 0.0)],
            current_variation_mps=0.3,
            current_variation_period_s=1200.0,
        )
    )
    t0, t1 = 100.0, 1000.0
    ts = np.linspace(t0, t1, 9001)
    # the current at the release point, integrated (the variation's phase held there: its 10 km wavelength)
    vel = np.array([env.current(t, 20.0, 30.0, 5.0)[:2] for t in ts])
    numeric = np.trapezoid(vel, ts, axis=0)
    assert env.current_displacement(5.0, 20.0, 30.0, t0, t1) == pytest.approx(tuple(numeric), abs=1e-3)


# ------------------------------------------------------------ TEOS-10
def test_sound_speed_is_teos10s_at_its_check_values():
    """TEOS-10's own check cast (gsw_cv_v3_0, shipped with gsw): from the cast's
    practical salinity, in-situ temperature, pressure and position, our
    conversions give TEOS-10's sound speed."""
    cv = np.load(Path(gsw.__file__).parent / "tests" / "gsw_cv_v3_0.npz")
    sp, t, p = cv["SP_chck_cast"], cv["t_chck_cast"], cv["p_chck_cast"]
    lat, lon = cv["lat_chck_cast"], cv["long_chck_cast"]
    ok = np.isfinite(cv["sound_speed"])
    got = teos10.sound_speed_p(t, sp, p, lat, lon)
    assert np.allclose(got[ok], cv["sound_speed"][ok], atol=cv["sound_speed_ca"])
    assert np.allclose(teos10.conductivity_s_per_m(sp, t, p)[ok] * 10.0, cv["C_from_SP"][ok], atol=cv["C_from_SP_ca"])


def test_sound_speed_of_standard_water_against_an_independent_formula():
    """35 PSU, 10 degC, 1000 dbar: TEOS-10 gives 1506.14 m/s; Mackenzie's (1981)
    nine-term equation, a fit to older data in depth, agrees within its error."""
    depth = float(teos10.depth_from_pressure(1000.0, LAT))
    c = float(teos10.sound_speed(10.0, 35.0, depth, LAT, LON))
    assert c == pytest.approx(1506.14, abs=0.01)
    T, S, D = 10.0, 35.0, depth
    mackenzie = (
        1448.96
        + 4.591 * T
        - 5.304e-2 * T**2
        + 2.374e-4 * T**3
        + 1.340 * (S - 35)
        + 1.630e-2 * D
        + 1.675e-7 * D**2
        - 1.025e-2 * T * (S - 35)
        - 7.139e-13 * T * D**3
    )
    assert c == pytest.approx(mackenzie, abs=0.2)
    # conductivity: PSS-78's definition, C(35, 15 degC, 0) = 4.2914 S/m
    assert float(teos10.conductivity_s_per_m(35.0, 15.0, 0.0)) == pytest.approx(4.2914, abs=5e-4)
    assert float(teos10.salinity_from_conductivity(4.2914, 15.0, 0.0)) == pytest.approx(35.0, abs=0.01)


def test_the_world_sound_speed_follows_the_water():
    env = Environment(EnvParams(ocean=ocean().params))
    # the surface water west of the front, and the deep water
    west = env.sound_speed(0.0, 0.0, 0.0, -300.0)
    deep = env.sound_speed(60.0, 0.0, 0.0, -300.0)
    assert west == pytest.approx(float(teos10.sound_speed(16.0, 32.5, 0.0, LAT, LON)), abs=1e-3)
    assert deep == pytest.approx(float(teos10.sound_speed(8.0, 35.0, 60.0, LAT, LON)), abs=1e-3)
    assert west - deep > 15.0  # warm over cold: slower below the thermocline


def test_travel_speed_is_the_harmonic_mean_along_the_path():
    env = Environment(EnvParams(ocean=ocean().params))
    a, b = (0.0, -300.0, 2.0), (0.0, -300.0, 58.0)
    depths = np.linspace(2.0, 58.0, 20001)
    c = np.array([env.sound_speed(d, 0.0, 0.0, -300.0) for d in depths[::400]])
    fine = env.ocean.sound_speeds(0.0, 0.0, -300.0, depths)
    exact = 1.0 / np.mean(1.0 / fine)  # the travel time's speed
    got = env.path_sound_speed(0.0, a, b)
    assert got == pytest.approx(exact, abs=0.05)
    assert c.min() < got < c.max()
    assert got < np.mean(fine)  # harmonic below arithmetic
    # across the front horizontally, too
    h = env.path_sound_speed(0.0, (0.0, 0.0, 1.0), (0.0, 400.0, 1.0))
    assert env.sound_speed(1.0, 0.0, 0.0, 400.0) < h < env.sound_speed(1.0, 0.0, 0.0, 0.0)


def test_lbl_travel_times_use_the_oceans_profile():
    params = EnvParams(
        ocean=ocean().params,
        transponders=[Transponder(1, 0.0, -300.0, 55.0, 0.05), Transponder(2, 300.0, 100.0, 50.0, 0.1)],
    )
    env = Environment(params)
    s = Lbl(LblConfig(rate_hz=1.0, noise=0.0, outlier_probability=0.0), 1, "AUV1", env)
    tr = Truth(t=0.0, eta=(0.0, -300.0, 5.0, 0, 0, 0), nu=(0.0,) * 6)
    _, m = s.measure(tr)
    for k, x in enumerate(params.transponders):
        a, b = (0.0, -300.0, 5.0), (x.north_m, x.east_m, x.depth_m)
        c = env.path_sound_speed(0.0, a, b)
        assert m.two_way_travel_s[k] == pytest.approx(2 * math.dist(a, b) / c + x.turnaround_s, abs=1e-9)
        assert abs(c - 1500.0) > 3.0  # not the world's constant
    assert m.sound_speed_mps == pytest.approx(env.sound_speed(5.0, 0.0, 0.0, -300.0))


def test_modem_arrivals_use_the_oceans_profile():
    from auv import acoustic_frame_t, modem_status_t, modem_tx_t
    from sim.modem.config import ModemConfig
    from sim.modem.receiver import Receiver

    env = Environment(EnvParams(ocean=ocean().params))
    tx, rx_pos = (0.0, -300.0, 40.0), (600.0, 500.0, 3.0)
    rx = Receiver(ModemConfig(loss_at_zero=0.0, loss_at_max_range=0.0), "AUV2", 7, env, modem_status_t())
    f = acoustic_frame_t()
    f.tx_north_m, f.tx_east_m, f.tx_depth_m = tx
    f.source_level_db, f.src_vehicle, f.seq, f.kind = 185.0, "AUV1", 1, modem_tx_t.KIND_RAW
    f.n_bytes, f.payload = 3, b"abc"
    rx.hear(f)
    t, got = 0.0, []
    while not got and t < 5.0:
        t = round(t + 0.02, 9)
        got = rx.step(t, rx_pos)
    c = env.path_sound_speed(0.0, tx, rx_pos)
    d = math.dist(tx, rx_pos)
    assert len(got) == 1 and got[0].utime == int(round(d / c * 1e6))
    assert t - 0.02 < d / c <= t + 1e-9
    assert abs(d / c - d / 1500.0) > 0.001  # the constant would be early by more than a millisecond


# ------------------------------------------------------------ configuration
def cfg_errors(text: str, where: Path) -> list[str]:
    with pytest.raises(ConfigError) as exc:
        loads(text, where / "cfg.yaml")
    return exc.value.errors


def test_the_ocean_section_is_checked_key_by_key(tmp_path):
    text = (
        "environment:\n"
        "  ocean:\n"
        "    front: {widht_m: 3, amplitude_m: -1}\n"
        "    water_a: {temperature_c: 50}\n"
        "    plumes: [{radius_m: 0}]\n"
        "    grid_start: '2024-01-01'\n"
    )
    errs = cfg_errors(text, tmp_path)
    assert errs == [
        f"{tmp_path}/cfg.yaml:3:13: environment.ocean.front.widht_m: unknown key; did you mean 'width_m'?",
        f"{tmp_path}/cfg.yaml:3:38: environment.ocean.front.amplitude_m: must be >= 0",
        f"{tmp_path}/cfg.yaml:4:30: environment.ocean.water_a.temperature_c: must be in [-2.5, 40] [degC]",
        f"{tmp_path}/cfg.yaml:5:25: environment.ocean.plumes[0].radius_m: must be > 0",
        f"{tmp_path}/cfg.yaml:6:5: environment.ocean.grid_start: only for a grid file (ocean.grid)",
    ]
    cfg = loads("environment:\n  ocean: {}\n", tmp_path / "ok.yaml")
    assert cfg.env.ocean == OceanParams()


# ------------------------------------------------------------ NetCDF
def write_grid(path: Path, **change) -> Path:
    """A small CF file: temperature and salinity linear in time, depth, lat and lon
    (so linear interpolation is exact), on (time, depth, lat, lon)."""
    import xarray as xr

    time = np.array([0.0, 1.0, 2.0])  # hours since the reference
    depth = np.array([0.5, 10.0, 30.0, 80.0])
    lat = LAT + np.linspace(-0.01, 0.01, 5)
    lon = LON + np.linspace(-0.012, 0.012, 6)
    tt, dd, la, lo = np.meshgrid(time, depth, lat, lon, indexing="ij")
    temp = 15.0 + 0.5 * tt - 0.1 * dd + 100.0 * (la - LAT) + 50.0 * (lo - LON)
    salt = 34.0 + 0.1 * tt + 0.01 * dd - 20.0 * (la - LAT)
    ds = xr.Dataset(
        {
            "temp": (
                ("time", "depth", "lat", "lon"),
                temp,
                {"standard_name": "sea_water_temperature", "units": "degC"},
            ),
            "salt": (("time", "depth", "lat", "lon"), salt, {"standard_name": "sea_water_salinity", "units": "1e-3"}),
        },
        coords={
            "time": ("time", time, {"standard_name": "time", "units": "hours since 2024-06-01 00:00:00"}),
            "depth": ("depth", depth, {"standard_name": "depth", "units": "m", "positive": "down"}),
            "lat": ("lat", lat, {"standard_name": "latitude", "units": "degrees_north"}),
            "lon": ("lon", lon, {"standard_name": "longitude", "units": "degrees_east"}),
        },
    )
    for step in change.get("edit", ()):
        ds = step(ds)
    ds.to_netcdf(path, engine="netcdf4")
    return path


GRID_CFG = """simulation: {{duration_s: {duration}}}
environment:
  origin_latitude_deg: 41.52
  origin_longitude_deg: -70.67
  ocean:
    grid: {name}
{extra}"""


def grid_cfg(tmp_path: Path, name: str = "ocean.nc", duration: float = 3600.0, extra: str = ""):
    return loads(GRID_CFG.format(name=name, duration=duration, extra=extra), tmp_path / "cfg.yaml")


def test_a_netcdf_grid_round_trips_and_interpolates_in_space_and_time(tmp_path):
    write_grid(tmp_path / "ocean.nc")
    cfg = grid_cfg(tmp_path)
    env = Environment(cfg.env, tmp_path)
    g = env.ocean.grid
    # the point 100 m north, 80 m east, 20 m down, 45 min in
    n, e, d, t = 100.0, 80.0, 20.0, 2700.0
    from sim.geo import LocalFrame

    la, lo = LocalFrame(LAT, LON).to_latlon(n, e)
    want_t = 15.0 + 0.5 * 0.75 - 0.1 * d + 100.0 * (la - LAT) + 50.0 * (lo - LON)
    want_s = 34.0 + 0.1 * 0.75 + 0.01 * d - 20.0 * (la - LAT)
    assert env.temperature_salinity(t, n, e, d) == pytest.approx((want_t, want_s), abs=1e-9)
    # above its shallowest level the field is held (the mixed layer); its time axis starts at sim 0
    assert env.temperature_salinity(0.0, 0.0, 0.0, 0.0)[0] == pytest.approx(15.0 - 0.05)
    assert g.time_s[0] == 0.0 and g.time_s[-1] == 7200.0 and len(g.sha256) == 64
    # the message a multi-HIL client builds the same ocean from
    from auv import env_model_t

    m = env_model_t.decode(env.to_env_model(1, "S", 1).encode())
    assert m.ocean and m.ocean_grid_ref == "ocean.nc" and m.ocean_grid_sha256 == g.sha256
    again = Environment(Environment.params_from_env_model(m), tmp_path)
    assert again.temperature_salinity(t, n, e, d) == env.temperature_salinity(t, n, e, d)
    # grid_start places sim time 0 on the file's axis
    late = grid_cfg(tmp_path, duration=1800.0, extra="    grid_start: '2024-06-01T01:00:00'\n")
    assert Environment(late.env, tmp_path).temperature_salinity(0.0, n, e, d)[0] == pytest.approx(want_t + 0.125)


def test_conservative_temperature_absolute_salinity_and_metres_are_converted(tmp_path):
    import xarray as xr

    north = np.linspace(-200.0, 200.0, 5)
    east = np.linspace(-300.0, 300.0, 4)
    depth = np.array([0.0, 50.0, 100.0])
    shape = (depth.size, north.size, east.size)
    sa = np.full(shape, 35.2)
    ct = np.full(shape, 9.0)
    ds = xr.Dataset(
        {
            "CT": (("z", "y", "x"), ct, {"standard_name": "sea_water_conservative_temperature", "units": "degC"}),
            "SA": (("z", "y", "x"), sa, {"standard_name": "sea_water_absolute_salinity", "units": "g/kg"}),
        },
        coords={
            "z": ("z", -depth, {"axis": "Z", "units": "m", "positive": "up"}),
            "y": ("y", north, {"standard_name": "projection_y_coordinate", "units": "m"}),
            "x": ("x", east, {"standard_name": "projection_x_coordinate", "units": "m"}),
        },
    )
    ds.to_netcdf(tmp_path / "teos.nc")
    g = OceanGrid(tmp_path / "teos.nc", LAT, LON)
    temp, salt = g.sample(0.0, 0.0, 0.0, 100.0)
    p = float(gsw.p_from_z(-100.0, LAT))
    assert float(temp) == pytest.approx(float(gsw.t_from_CT(35.2, 9.0, p)), abs=1e-9)
    assert float(salt) == pytest.approx(float(gsw.SP_from_SA(35.2, p, LON, LAT)), abs=1e-9)
    assert g.static and g.north_m[0] == -200.0 and g.depth_m[-1] == 100.0


def drop(name):
    return lambda ds: ds.drop_vars(name)


def attrs(var, **kv):
    def edit(ds):
        a = dict(ds[var].attrs)
        for k, v in kv.items():
            if v is None:
                a.pop(k, None)
            else:
                a[k] = v
        ds[var].attrs = a
        return ds

    return edit


def nan_at(ds):
    ds["temp"][1, 2, 3, 4] = np.nan
    return ds


BAD_FILES = {
    "missing_temperature": (
        [drop("temp")],
        "no temperature variable: CF needs one with standard_name sea_water_temperature or "
        "sea_water_potential_temperature or sea_water_conservative_temperature; the file has salt (sea_water_salinity)",
    ),
    "missing_salinity": ([attrs("salt", standard_name=None)], "no salinity variable"),
    "temperature_without_units": (
        [attrs("temp", units=None)],
        "variable 'temp' has no units attribute (CF: degC or K)",
    ),
    "salinity_in_wrong_units": ([attrs("salt", units="g/kg")], "variable 'salt' has units 'g/kg': not a practical"),
    "time_without_units": ([attrs("time", units=None)], "coordinate 'time' has no units attribute"),
    "depth_without_units": ([attrs("depth", units=None)], "coordinate 'depth' has no units attribute (CF: m)"),
    "wrong_dimension_order": (
        [lambda ds: ds.transpose("lat", "lon", "depth", "time")],
        "'temp' has its dimensions in the order lat (y), lon (x), depth (depth), time (time): "
        "expected (time, depth, y, x), CF's T, Z, Y, X",
    ),
    "nan": (
        [nan_at],
        "variable 'temp' has 1 missing values (NaN or _FillValue), the first at index time=1, depth=2, y=3, x=4",
    ),
    "kelvin_mistaken": (
        [attrs("temp", units="K")],
        "variable 'temp' spans -267.75 to -255.6 degC, beyond what a sea holds (-3 to 45): wrong units?",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD_FILES))
def test_every_bad_file_is_refused_naming_the_file_and_the_problem(tmp_path, case):
    edits, problem = BAD_FILES[case]
    path = write_grid(tmp_path / "ocean.nc", edit=edits)
    errs = cfg_errors(GRID_CFG.format(name="ocean.nc", duration=600, extra=""), tmp_path)
    assert len(errs) == 1, errs
    assert errs[0].startswith(f"{tmp_path}/cfg.yaml:6:11: environment.ocean.grid: {path}: "), errs[0]
    assert problem in errs[0], errs[0]
    with pytest.raises(OceanError, match=str(path)):
        OceanGrid(path, LAT, LON)


def test_a_file_that_is_not_netcdf_or_not_there_is_refused(tmp_path):
    (tmp_path / "ocean.nc").write_text("time,depth,temp\n0,1,12\n")
    errs = cfg_errors(GRID_CFG.format(name="ocean.nc", duration=600, extra=""), tmp_path)
    assert errs == [
        f"{tmp_path}/cfg.yaml:6:11: environment.ocean.grid: {tmp_path}/ocean.nc: not a NetCDF file "
        "(it starts with neither 'CDF' nor the HDF5 signature)"
    ]
    errs = cfg_errors(GRID_CFG.format(name="nowhere.nc", duration=600, extra=""), tmp_path)
    assert errs == [
        f"{tmp_path}/cfg.yaml:6:11: environment.ocean.grid: {tmp_path}/nowhere.nc: "
        "cannot read the ocean grid (No such file or directory)"
    ]


@pytest.mark.parametrize(
    "extra,duration,problem",
    [
        (
            "initial: {north_m: 2000}\n",
            600,
            "does not cover the vehicle's start and the transponders: the grid covers north",
        ),
        ("", 9000, "the grid's times end 7200 s after sim time 0, the run lasts 9000 s"),
        ("", 600, "the grid's deepest level is 80 m, the area needs 120 m"),
        ("", 600, "does not cover the area (ocean.area): the grid covers east"),
    ],
    ids=["start", "time", "depth", "area"],
)
def test_a_grid_that_does_not_cover_the_area_is_refused(tmp_path, extra, duration, problem):
    write_grid(tmp_path / "ocean.nc")
    text = GRID_CFG.format(name="ocean.nc", duration=duration, extra="")
    if "deepest" in problem:
        text += "    area: {max_depth_m: 120}\n"
    if "ocean.area" in problem:
        text += "    area: {east_m: [-100, 5000]}\n"
    errs = cfg_errors(extra + text, tmp_path)
    assert len(errs) == 1 and "environment.ocean.grid:" in errs[0] and problem in errs[0], errs


def test_a_grid_beside_the_analytic_fields_is_refused(tmp_path):
    write_grid(tmp_path / "ocean.nc")
    errs = cfg_errors(GRID_CFG.format(name="ocean.nc", duration=600, extra="    front: {offset_m: 3}\n"), tmp_path)
    assert errs == [
        f"{tmp_path}/cfg.yaml:7:5: environment.ocean.front: the grid file gives the water: "
        "no analytic front, water masses or thermocline beside it"
    ]


def test_the_launcher_names_an_ocean_grid_from_the_merged_files_folder(tmp_path):
    """A scenario's run folder holds the merged configuration: a grid named
    relative to its own file is made absolute there, as a bathymetry grid is."""
    from tools.launch.simconfig import _absolute_grid

    env = {"ocean": {"grid": "worlds/bay.nc", "plumes": []}, "bathymetry": {"grid": "b.npz"}, "seed": 3}
    out = _absolute_grid(env, tmp_path)
    assert out["ocean"] == {"grid": str((tmp_path / "worlds" / "bay.nc").resolve()), "plumes": []}
    assert out["bathymetry"]["grid"] == str((tmp_path / "b.npz").resolve()) and out["seed"] == 3
    assert _absolute_grid({"ocean": {"front": {"offset_m": 1}}}, tmp_path) == {"ocean": {"front": {"offset_m": 1}}}

"""Seawater by TEOS-10 (the `gsw` package, the Gibbs SeaWater toolbox).

The world holds in-situ temperature t [degC, ITS-90] and practical salinity
SP [PSU, PSS-78], as a CTD measures them. TEOS-10's functions want absolute
salinity SA [g/kg] and conservative temperature CT [degC] at sea pressure p
[dbar]; the conversions are gsw's:

    p  = gsw.p_from_z(-depth, lat)          depth [m, down] -> sea pressure
    SA = gsw.SA_from_SP(SP, p, lon, lat)    (the absolute-salinity anomaly atlas)
    CT = gsw.CT_from_t(SA, t, p)
    c  = gsw.sound_speed(SA, CT, p)

Conductivity is PSS-78's: gsw.C_from_SP / gsw.SP_from_C, in mS/cm there, S/m
here (1 S/m = 10 mS/cm). Every function takes floats or numpy arrays.
"""

from __future__ import annotations

import gsw
import numpy as np

try:  # gsw.p_from_z's own ufunc: its Python wrapper spends 70 us a call checking z with numpy.ma
    from gsw._gsw_ufuncs import p_from_z as _p_from_z
except ImportError:  # pragma: no cover - another gsw layout

    def _p_from_z(z, lat, geo_strf_dyn_height, sea_surface_geopotential):
        return gsw.p_from_z(z, lat, geo_strf_dyn_height, sea_surface_geopotential)


MS_PER_CM_PER_S_PER_M = 10.0  # 1 S/m = 10 mS/cm


def pressure_dbar(depth_m, lat_deg: float):
    """Sea pressure at a depth (positive down) [dbar] (gsw.p_from_z)."""
    return _p_from_z(-np.asarray(depth_m, float), lat_deg, 0.0, 0.0)


def depth_from_pressure(p_dbar, lat_deg: float):
    """Depth (positive down) of a sea pressure [m]."""
    return -gsw.z_from_p(p_dbar, lat_deg)


def sound_speed(t_c, sp_psu, depth_m, lat_deg: float, lon_deg: float):
    """Speed of sound in seawater of in-situ temperature t and practical salinity
    SP at a depth [m/s] (TEOS-10)."""
    p = pressure_dbar(depth_m, lat_deg)
    return sound_speed_p(t_c, sp_psu, p, lat_deg, lon_deg)


def sound_speed_p(t_c, sp_psu, p_dbar, lat_deg: float, lon_deg: float):
    """sound_speed() at a sea pressure [dbar] instead of a depth."""
    sa = gsw.SA_from_SP(sp_psu, p_dbar, lon_deg, lat_deg)
    ct = gsw.CT_from_t(sa, t_c, p_dbar)
    return gsw.sound_speed(sa, ct, p_dbar)


def conductivity_s_per_m(sp_psu, t_c, p_dbar):
    """Electrical conductivity of seawater [S/m] (PSS-78)."""
    return gsw.C_from_SP(sp_psu, t_c, p_dbar) / MS_PER_CM_PER_S_PER_M


def salinity_from_conductivity(c_s_per_m, t_c, p_dbar):
    """Practical salinity from conductivity [S/m], temperature and pressure (PSS-78)."""
    return gsw.SP_from_C(np.asarray(c_s_per_m, float) * MS_PER_CM_PER_S_PER_M, t_c, p_dbar)


def in_situ_from_conservative(sa, ct, p_dbar):
    """In-situ temperature from absolute salinity and conservative temperature."""
    return gsw.t_from_CT(sa, ct, p_dbar)


def in_situ_from_potential(sa, pt, p_dbar):
    """In-situ temperature from absolute salinity and potential temperature (p_ref 0)."""
    return gsw.t_from_CT(sa, gsw.CT_from_pt(sa, pt), p_dbar)


def practical_from_absolute(sa, p_dbar, lon_deg, lat_deg):
    """Practical salinity from absolute salinity [g/kg]."""
    return gsw.SP_from_SA(sa, p_dbar, lon_deg, lat_deg)


def absolute_from_practical(sp, p_dbar, lon_deg, lat_deg):
    return gsw.SA_from_SP(sp, p_dbar, lon_deg, lat_deg)

#include "drivers/ctd/pss78.h"

#include <math.h>

#define C_35_15_0 4.2914 /* conductivity of standard seawater, S = 35 at 15 degC (IPTS-68), 0 dbar [S/m] */

/* rt(T): the conductivity ratio of standard seawater at T to that at 15 degC */
static double rt_of(double t68)
{
    return 0.6766097 + t68 * (2.00564e-2 + t68 * (1.104259e-4 + t68 * (-6.9698e-7 + t68 * 1.0031e-9)));
}

double pss78_salinity(double conductivity_s_per_m, double temperature_c, double pressure_dbar)
{
    if (!(conductivity_s_per_m >= 0) || !isfinite(temperature_c) || !isfinite(pressure_dbar))
        return NAN;
    const double t = 1.00024 * temperature_c; /* ITS-90 -> IPTS-68, which PSS-78 is written in */
    const double p = pressure_dbar;
    const double r = conductivity_s_per_m / C_35_15_0;
    const double rp = 1.0 + p * (2.070e-5 + p * (-6.370e-10 + p * 3.989e-15)) /
                                (1.0 + t * (3.426e-2 + t * 4.464e-4) + r * (4.215e-1 - 3.107e-3 * t));
    const double rt = r / (rp * rt_of(t));
    if (!(rt > 0))
        return NAN;
    const double q = sqrt(rt);
    const double dt = t - 15.0;
    const double ds = dt / (1.0 + 0.0162 * dt) *
                      (0.0005 + q * (-0.0056 + q * (-0.0066 + q * (-0.0375 + q * (0.0636 + q * -0.0144)))));
    const double s = 0.0080 + q * (-0.1692 + q * (25.3851 + q * (14.0941 + q * (-7.0261 + q * 2.7081)))) + ds;
    return s >= 2.0 && s <= 42.0 ? s : NAN;
}

double pss78_depth(double pressure_dbar, double latitude_deg)
{
    const double x = sin(latitude_deg * M_PI / 180.0);
    const double x2 = x * x;
    const double p = pressure_dbar;
    const double g = 9.780318 * (1.0 + (5.2788e-3 + 2.36e-5 * x2) * x2) + 1.092e-6 * p;
    return (((-1.82e-15 * p + 2.279e-10) * p - 2.2512e-5) * p + 9.72659) * p / g;
}

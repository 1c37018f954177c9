#include "frontest/front_model.hpp"

#include <cmath>
#include <utility>

namespace frontest {

namespace {
constexpr double kTwoPi = 6.283185307179586;
constexpr double kPi = 3.141592653589793;

double wrap_2pi(double a)
{
    a = std::fmod(a, kTwoPi);
    return a < 0 ? a + kTwoPi : a;
}
}  // namespace

Vec to_q(const Front &f)
{
    Vec q(f.meander ? kMeanderParams : kStraightParams);
    q[OFFSET] = f.offset_m;
    q[ANGLE] = f.angle_rad;
    q[TA] = f.ta_c;
    q[TB] = f.tb_c;
    q[LOG_WIDTH] = std::log(f.width_m);
    if (f.meander) {
        q[AMPLITUDE] = f.amplitude_m;
        q[LOG_WAVELENGTH] = std::log(f.wavelength_m);
        q[PHASE] = f.phase_rad;
    }
    return q;
}

Front from_q(const Vec &q)
{
    Front f;
    f.offset_m = q[OFFSET];
    f.angle_rad = q[ANGLE];
    f.ta_c = q[TA];
    f.tb_c = q[TB];
    f.width_m = std::exp(q[LOG_WIDTH]);
    f.meander = q.size() == kMeanderParams;
    if (f.meander) {
        f.amplitude_m = q[AMPLITUDE];
        f.wavelength_m = std::exp(q[LOG_WAVELENGTH]);
        f.phase_rad = q[PHASE];
    }
    return f;
}

Front canonical(Front f)
{
    if (f.meander && f.amplitude_m < 0) {
        f.amplitude_m = -f.amplitude_m;
        f.phase_rad += kPi;
    }
    // angle + pi turns s and r into -s and -r; with offset -> -offset and
    // phase -> -phase, x turns into -x, which the swapped waters undo
    double a = std::remainder(f.angle_rad, kTwoPi);  // (-pi, pi]
    if (a < -kPi / 2 || a >= kPi / 2) {
        a = a >= kPi / 2 ? a - kPi : a + kPi;
        f.offset_m = -f.offset_m;
        std::swap(f.ta_c, f.tb_c);
        if (f.meander)
            f.phase_rad = -f.phase_rad;
    }
    f.angle_rad = a;
    if (f.meander)
        f.phase_rad = wrap_2pi(f.phase_rad);
    return f;
}

void front_frame(double angle, double n, double e, double &s, double &r)
{
    const double c = std::cos(angle), sn = std::sin(angle);
    s = n * c + e * sn;
    r = -n * sn + e * c;
}

double model(const Vec &q, double n, double e, double *grad)
{
    double s, r;
    front_frame(q[ANGLE], n, e, s, r);
    const bool meander = q.size() == kMeanderParams;
    double x = r - q[OFFSET], psi = 0, L = 0, A = 0;
    if (meander) {
        A = q[AMPLITUDE];
        L = std::exp(q[LOG_WAVELENGTH]);
        psi = kTwoPi * s / L + q[PHASE];
        x -= A * std::sin(psi);
    }
    const double w = std::exp(q[LOG_WIDTH]);
    const double u = std::tanh(x / w);
    const double ta = q[TA], tb = q[TB];
    const double t = ta + (tb - ta) * 0.5 * (1.0 + u);
    if (grad) {
        const double dT_dx = (tb - ta) * 0.5 * (1.0 - u * u) / w;
        // ds/dangle = r, dr/dangle = -s
        double dx_dangle = -s;
        if (meander)
            dx_dangle -= A * std::cos(psi) * kTwoPi / L * r;
        grad[OFFSET] = -dT_dx;
        grad[ANGLE] = dT_dx * dx_dangle;
        grad[TA] = 0.5 * (1.0 - u);
        grad[TB] = 0.5 * (1.0 + u);
        grad[LOG_WIDTH] = -dT_dx * x;  // d/d ln w of tanh(x / w) = -(x / w) sech^2
        if (meander) {
            grad[AMPLITUDE] = -dT_dx * std::sin(psi);
            grad[LOG_WAVELENGTH] = dT_dx * A * std::cos(psi) * kTwoPi * s / L;  // d psi / d ln L = -2 pi s / L
            grad[PHASE] = -dT_dx * A * std::cos(psi);
        }
    }
    return t;
}

}  // namespace frontest

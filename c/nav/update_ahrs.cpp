// Compass heading: z = psi + b + noise. Roll, pitch and the body rates of
// the same message become the inputs of the following predictions.
#include <cmath>

#include "nav/ekf_predict.hpp"
#include "nav/nav_updates.hpp"

namespace nav {

namespace {

// Heading from the compass given the current bias estimate: the heading then
// carries the bias's uncertainty, anti-correlated with it (their sum is what
// the compass knows to its noise).
void align_heading(FilterState &s, double z, const NavConfig &c)
{
    const double vb = s.P(BIAS, BIAS);
    reset_state(s, PSI, wrap_2pi(z - s.x(BIAS)), vb + c.compass_noise_rad * c.compass_noise_rad);
    s.P(PSI, BIAS) = s.P(BIAS, PSI) = -vb;
    s.heading_init = true;
}

}  // namespace

Outcome update_ahrs(FilterState &s, const AhrsMeas &m, int64_t utime, const NavConfig &c)
{
    Outcome o;
    s.in.roll_rad = m.roll_rad;
    s.in.pitch_rad = m.pitch_rad;
    s.in.p_radps = m.p_radps;
    s.in.q_radps = m.q_radps;
    s.in.r_radps = m.r_radps;
    s.in.gyro_utime = utime;
    s.last_meas_utime[SENSOR_AHRS] = utime;
    if (!s.heading_init) {
        align_heading(s, m.heading_rad, c);
        s.last_accept_utime[SENSOR_AHRS] = utime;
        o.initialised = true;
        o.accepted = 1;
        return o;
    }
    Eigen::Matrix<double, 1, 1> y, R;
    Eigen::Matrix<double, 1, N> H = Eigen::Matrix<double, 1, N>::Zero();
    y(0) = wrap_pi(m.heading_rad - (s.x(PSI) + s.x(BIAS)));
    H(PSI) = 1;
    H(BIAS) = 1;
    R(0) = c.compass_noise_rad * c.compass_noise_rad;
    const Gated g = kalman_update<1>(s, y, H, R, c.gate_chi2[1], kConsiderBias);
    s.x(PSI) = wrap_2pi(s.x(PSI));
    if (record_gated(s, SENSOR_AHRS, g, utime, c, o))
        align_heading(s, m.heading_rad, c);
    return o;
}

}  // namespace nav

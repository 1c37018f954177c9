// Pressure depth: z = depth + noise.
#include "nav/ekf_predict.hpp"
#include "nav/nav_updates.hpp"

namespace nav {

Outcome update_depth(FilterState &s, const DepthMeas &m, int64_t utime, const NavConfig &c)
{
    Outcome o;
    const double r = c.depth_noise_m * c.depth_noise_m;
    s.last_meas_utime[SENSOR_DEPTH] = utime;
    if (!s.depth_init) {
        reset_state(s, PD, m.depth_m, r);
        s.depth_init = true;
        s.last_accept_utime[SENSOR_DEPTH] = utime;
        o.initialised = true;
        o.accepted = 1;
        return o;
    }
    Eigen::Matrix<double, 1, 1> y, R;
    Eigen::Matrix<double, 1, N> H = Eigen::Matrix<double, 1, N>::Zero();
    y(0) = m.depth_m - s.x(PD);
    H(PD) = 1;
    R(0) = r;
    const Gated g = kalman_update<1>(s, y, H, R, c.gate_chi2[1], kConsiderBias);
    if (record_gated(s, SENSOR_DEPTH, g, utime, c, o))
        reset_state(s, PD, m.depth_m, r);
    return o;
}

}  // namespace nav

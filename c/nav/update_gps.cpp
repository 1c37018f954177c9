// GPS fix (surfaced only): z = (north, east) + noise. The first fix aligns
// the position unless the configuration gave an initial position.
#include "nav/ekf_predict.hpp"
#include "nav/nav_updates.hpp"

namespace nav {

Outcome update_gps(FilterState &s, const GpsMeas &m, int64_t utime, const NavConfig &c)
{
    Outcome o;
    const double sigma = m.sigma_m > 0 ? m.sigma_m : c.gps_noise_m;
    const double r = sigma * sigma;
    s.last_meas_utime[SENSOR_GPS] = utime;
    if (!s.position_init) {
        reset_state(s, PN, m.north_m, r);
        reset_state(s, PE, m.east_m, r);
        s.position_init = true;
        s.last_accept_utime[SENSOR_GPS] = utime;
        o.initialised = true;
        o.accepted = 1;
        return o;
    }
    Eigen::Vector2d y(m.north_m - s.x(PN), m.east_m - s.x(PE));
    Eigen::Matrix<double, 2, N> H = Eigen::Matrix<double, 2, N>::Zero();
    H(0, PN) = 1;
    H(1, PE) = 1;
    const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * r;
    const Gated g = kalman_update<2>(s, y, H, R, c.gate_chi2[2]);
    if (record_gated(s, SENSOR_GPS, g, utime, c, o)) {
        // Fix after fix disagrees with the estimate: the dead reckoning is
        // what went wrong, so the position starts again from the fix.
        reset_state(s, PN, m.north_m, r);
        reset_state(s, PE, m.east_m, r);
    }
    return o;
}

}  // namespace nav

#include "nav/nav_status.hpp"

#include <algorithm>
#include <cmath>

namespace nav {

namespace {

bool within(int64_t then, int64_t now, double window_s)
{
    return then >= 0 && static_cast<double>(now - then) * 1e-6 <= window_s;
}

bool numerically_sound(const FilterState &s)
{
    if (!s.x.allFinite() || !s.P.allFinite())
        return false;
    for (int i = 0; i < N; i++)
        if (!(s.P(i, i) > 0))
            return false;
    return true;
}

}  // namespace

NavStatus evaluate_status(const FilterState &s, int64_t now, const NavConfig &c)
{
    NavStatus st;
    const bool aligned = s.aligned();
    if (aligned)
        st.bits |= STATUS_ALIGNED;
    if (within(s.last_bottom_lock_utime, now, c.aid_window_s[SENSOR_DVL]))
        st.bits |= STATUS_DVL_BOTTOM;
    if (within(s.last_water_track_utime, now, c.aid_window_s[SENSOR_DVL]))
        st.bits |= STATUS_DVL_WATER;
    if (within(s.last_accept_utime[SENSOR_GPS], now, c.aid_window_s[SENSOR_GPS]))
        st.bits |= STATUS_GPS;
    if (within(s.last_accept_utime[SENSOR_LBL], now, c.aid_window_s[SENSOR_LBL]))
        st.bits |= STATUS_LBL;

    st.position_sigma_m = std::sqrt(std::max(0.0, s.P(PN, PN) + s.P(PE, PE)));
    st.heading_sigma_rad = std::sqrt(std::max(0.0, s.P(PSI, PSI)));
    int64_t last_any = -1;
    for (int k = 0; k < kSensors; k++)
        last_any = std::max(last_any, s.last_meas_utime[k]);

    const bool invalid = !aligned || !numerically_sound(s) || st.position_sigma_m > c.invalid_sigma_m ||
                         !within(s.last_accept_utime[SENSOR_AHRS], now, c.heading_timeout_s) ||
                         !within(last_any, now, c.input_timeout_s);
    const bool degraded = st.position_sigma_m > c.degraded_sigma_m ||
                          st.heading_sigma_rad > c.degraded_heading_sigma_rad || !s.depth_init ||
                          !within(s.last_accept_utime[SENSOR_DVL], now, c.dvl_timeout_s);
    if (invalid)
        st.bits |= STATUS_INVALID;
    if (degraded)
        st.bits |= STATUS_DEGRADED;
    st.trusted = aligned && !invalid && !degraded;
    return st;
}

}  // namespace nav

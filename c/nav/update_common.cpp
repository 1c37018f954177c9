#include "nav/nav_updates.hpp"

namespace nav {

const char *sensor_name(int sensor)
{
    static const char *const names[kSensors] = {"ahrs", "depth", "dvl", "gps", "lbl"};
    return sensor >= 0 && sensor < kSensors ? names[sensor] : "?";
}

bool record_gated(FilterState &s, int k, const Gated &g, int64_t utime, const NavConfig &c, Outcome &o)
{
    s.last_nis[k] = g.nis;
    o.nis = g.nis;
    if (g.accepted) {
        o.accepted++;
        s.consecutive_rejects[k] = 0;
        s.last_accept_utime[k] = utime;
        return false;
    }
    o.rejected++;
    if (++s.consecutive_rejects[k] < c.reset_after[k])
        return false;
    s.consecutive_rejects[k] = 0;
    o.reset = true;
    return true;
}

}  // namespace nav

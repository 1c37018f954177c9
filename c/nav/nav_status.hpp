// What the filter says about itself: the status bits of nav_solution_t and
// whether plans should trust it (nav_filter_status_t.trusted).
#ifndef NAV_STATUS_HPP
#define NAV_STATUS_HPP

#include <cstdint>

#include "nav/ekf_state.hpp"
#include "nav/nav_config.hpp"

namespace nav {

// Same values as auv.nav_solution_t's STATUS_* constants (checked where
// the two meet, in nav_lcm.cpp).
enum StatusBit : int32_t {
    STATUS_ALIGNED = 1,
    STATUS_DVL_BOTTOM = 2,
    STATUS_DVL_WATER = 4,
    STATUS_GPS = 8,
    STATUS_LBL = 16,
    STATUS_DEGRADED = 32,
    STATUS_INVALID = 64,
};

struct NavStatus {
    int32_t bits = 0;
    bool trusted = false;       // aligned, neither DEGRADED nor INVALID
    double position_sigma_m = 0;        // sqrt(P_nn + P_ee)
    double heading_sigma_rad = 0;
};

// s is the estimate at now (already predicted there).
NavStatus evaluate_status(const FilterState &s, int64_t now, const NavConfig &c);

}  // namespace nav

#endif

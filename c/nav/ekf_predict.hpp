// Time update: dead reckoning between measurements.
#ifndef NAV_EKF_PREDICT_HPP
#define NAV_EKF_PREDICT_HPP

#include "nav/ekf_state.hpp"
#include "nav/nav_config.hpp"

namespace nav {

// Start a state: zero mean, the configured prior variances; heading and
// position wait for their first measurement.
void init_state(FilterState &s, const NavConfig &cfg);

// Advance s to utime (never backwards), in steps of at most
// cfg.max_predict_step_s.
void predict(FilterState &s, int64_t utime, const NavConfig &cfg);

// Re-initialise state i from a direct measurement: mean value, variance var,
// and no correlation with the rest (used by alignment and resets).
void reset_state(FilterState &s, int i, double value, double var);

}  // namespace nav

#endif

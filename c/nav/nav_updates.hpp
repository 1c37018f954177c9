// One measurement update per sensor. Each gates its innovation, keeps the
// per-sensor book (accepted time, last NIS, consecutive rejections) in the
// state so a replay reproduces it, initialises the states it observes
// directly the first time, and re-initialises them after too many
// consecutive rejections (the filter, not the sensor, is then assumed wrong).
// The caller has already predicted the state to the measurement's time.
#ifndef NAV_UPDATES_HPP
#define NAV_UPDATES_HPP

#include "nav/ekf_state.hpp"
#include "nav/ekf_update.hpp"
#include "nav/nav_config.hpp"

namespace nav {

// The compass bias is a consider state of every update but the position
// fixes (GPS, LBL): it is observable only through where the vehicle went, and
// letting velocity, depth or compass innovations move it through their
// correlations makes it absorb unmodelled water motion (wave orbital
// velocity, shear seen in water track): in the simulated swell the bias
// estimate drifted 0.5 deg the wrong way in every dive, which dead reckoning
// then turned into cross-track error.
constexpr uint32_t kConsiderBias = 1u << BIAS;

struct Outcome {
    int accepted = 0, rejected = 0;     // scalar/vector updates (LBL: one per reply)
    int unknown = 0;                    // LBL replies from transponders not in the config
    bool initialised = false;           // the measurement initialised states
    bool reset = false;                 // ... or re-initialised them after rejections
    double nis = 0;                     // of the last gated update
    // LBL, per reply of the message (in its order): the range, its
    // innovation, NIS and fate (-1 not used: unknown id or no position yet)
    double reply_range_m[kMaxReplies] = {};
    double reply_innovation_m[kMaxReplies] = {};
    double reply_nis[kMaxReplies] = {};
    int8_t reply_accepted[kMaxReplies] = {};
};

Outcome update_ahrs(FilterState &s, const AhrsMeas &m, int64_t utime, const NavConfig &c);
Outcome update_depth(FilterState &s, const DepthMeas &m, int64_t utime, const NavConfig &c);
Outcome update_dvl(FilterState &s, const DvlMeas &m, int64_t utime, const NavConfig &c);
Outcome update_gps(FilterState &s, const GpsMeas &m, int64_t utime, const NavConfig &c);
Outcome update_lbl(FilterState &s, const LblMeas &m, int64_t utime, const NavConfig &c);

// Book-keeping after one gated update of sensor k. Returns true when the
// consecutive rejections reached the configured reset count (and clears it).
bool record_gated(FilterState &s, int k, const Gated &g, int64_t utime, const NavConfig &c, Outcome &o);

}  // namespace nav

#endif

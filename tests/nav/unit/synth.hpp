// A synthetic vehicle for the unit tests: straight and level at constant
// speed (optionally turning at a constant rate), and what its sensors would
// report, with seeded Gaussian noise. Fast enough for Monte Carlo runs.
#ifndef NAV_UNIT_SYNTH_HPP
#define NAV_UNIT_SYNTH_HPP

#include <random>
#include <vector>

#include "nav/nav_config.hpp"
#include "nav/nav_meas.hpp"

struct SynthTruth {
    double t, n, e, d, psi, u;
};

struct Synth {
    double speed = 1.5, heading = 0.3, depth = 10.0, turn_rate = 0.0;
    double compass_bias = 0.0;      // the truth; the filter only knows its sigma
    double compass_noise = 0.00872665, dvl_noise = 0.01, depth_noise = 0.02, gps_noise = 2.0;
    double lbl_noise = 1.25, sound_speed = 1500.0;
    double gps_until_s = 0.0;       // GPS fixes (1 Hz) while t < this
    double lbl_period_s = 0.0;      // 0: no LBL
    std::mt19937_64 rng{1};

    SynthTruth truth(double t) const;
    double gauss(double sigma);
    // Every measurement from 0 to duration_s, sorted by time.
    std::vector<nav::Measurement> run(double duration_s, const nav::NavConfig &cfg);
    // One LBL ping at t to every configured transponder (exact + noise).
    nav::Measurement lbl_ping(double t, const nav::NavConfig &cfg);
};

nav::NavConfig synth_config();      // three transponders around the track

#endif

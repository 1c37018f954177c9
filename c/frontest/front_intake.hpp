// What the estimator fits: the vehicle's CTD readings, each placed at the
// navigated position of its time, averaged in bins of along-path distance,
// within a window of time. Every reading that is not used is counted by its
// reason. Pure: the process (front_node) hands it messages and the clock.
//
//  - a reading marked not valid: not_valid;
//  - a temperature outside -3 to 45 degC or a depth outside -5 to 11000 m
//    (or either not a number): out_of_range (what a sea holds);
//  - deeper than max_depth_m: below_layer (the model is of the upper water);
//  - older than max_age_s on arrival, or since (its bin ages out, or the
//    oldest bins make room for newer ones): too_old;
//  - no navigation around its time: no_position. A reading waits up to
//    position_wait_s of the clock for the navigation of its time; it is placed
//    by interpolating the two solutions around it if they are at most
//    nav_gap_s apart. A solution marked invalid is not a position.
#ifndef FRONTEST_FRONT_INTAKE_HPP
#define FRONTEST_FRONT_INTAKE_HPP

#include <cstdint>
#include <deque>
#include <vector>

#include "frontest/front_model.hpp"

namespace frontest {

struct IntakeOptions {
    double max_age_s = 1800;
    double max_depth_m = 15;
    double bin_m = 1.0;             // a bin closes when the vehicle has moved this far ...
    double bin_max_s = 10;          // ... or after this long (a vehicle holding station)
    double position_wait_s = 1.0;
    double nav_gap_s = 2.0;
    size_t max_bins = 8000;
};

struct Drops {
    int64_t not_valid = 0, out_of_range = 0, no_position = 0, too_old = 0, below_layer = 0, time_rule = 0;
};

class Intake {
public:
    explicit Intake(const IntakeOptions &opt) : opt_(opt) {}

    // A navigation solution (usable: not marked invalid).
    void nav(int64_t t, double north_m, double east_m, bool usable);
    // A CTD reading.
    void ctd(int64_t t, double temperature_c, double depth_m, bool valid);
    // The clock: places the waiting readings, ages the bins.
    void advance(int64_t now);
    void count_time_rule() { drops_.time_rule++; }

    // One sample per bin, oldest first (the bin being filled too).
    std::vector<Sample> samples() const;
    const Drops &drops() const { return drops_; }
    int64_t readings_used() const;

private:
    struct NavPoint {
        int64_t t;
        double n, e;
    };
    struct Reading {
        int64_t t;
        double temperature_c;
    };
    struct Bin {
        double n = 0, e = 0, temp = 0, t = 0;   // sums
        int count = 0;
        double first_n = 0, first_e = 0;
        int64_t first_t = 0, last_t = 0;
    };
    void place(const Reading &r, double n, double e);
    bool have_now_ = false;
    int64_t now_ = 0;
    IntakeOptions opt_;
    std::deque<NavPoint> nav_;
    std::deque<Reading> pending_;
    std::deque<Bin> bins_;          // closed, oldest first
    Bin open_;
    Drops drops_;
};

}  // namespace frontest

#endif

// The navigation filter: measurements in (any order, each with its time of
// validity), a time-ordered EKF estimate out. A measurement older than the
// newest processed one is inserted at its time and everything after it is
// processed again from the stored state (so an LBL ping stamped seconds ago
// counts exactly as if it had arrived on time); one older than the history
// window is dropped and counted. Nothing is allocated after construction.
#ifndef NAV_FILTER_HPP
#define NAV_FILTER_HPP

#include <cstdint>

#include "nav/history.hpp"
#include "nav/nav_config.hpp"
#include "nav/nav_updates.hpp"

namespace nav {

struct SensorStats {
    uint64_t measurements = 0;  // pushed
    uint64_t accepted = 0, rejected = 0;        // gated updates (LBL: per reply)
    uint64_t unknown = 0;       // LBL replies from unconfigured transponders
    uint64_t resets = 0;        // re-initialisations after consecutive rejections
    uint64_t too_old = 0;       // arrived after the history window: dropped
};

struct FilterStats {
    SensorStats sensor[kSensors];
    uint64_t out_of_order = 0;  // arrived after a younger measurement
    uint64_t replayed = 0;      // measurements processed again because of those
    uint64_t numeric_resets = 0;        // state went non-finite: started again unaligned
};

class NavFilter {
public:
    explicit NavFilter(const NavConfig &cfg, size_t history_capacity = 1024);

    // Process one measurement in time order; returns its own outcome (a
    // replay of later measurements is not counted again in the stats).
    Outcome push(const Measurement &m);

    const FilterState &state() const { return cur_; }
    const FilterStats &stats() const { return stats_; }
    const NavConfig &config() const { return cfg_; }

    // The estimate at utime: predicted on a copy when utime is later than
    // the newest measurement, else the current state as it is.
    void estimate_at(int64_t utime, FilterState &out) const;

    // Height above the seabed is not a filter state (the seabed is not
    // modelled): the newest altimeter or DVL range, moved by the vehicle's
    // depth change since, while younger than altitude_timeout_s.
    void note_altitude(int64_t utime, double altitude_m);
    double altitude_at(const FilterState &est) const;      // -1: unknown

private:
    void apply(FilterState &s, const Measurement &m, Outcome *o) const;
    void trim();
    void restart();

    NavConfig cfg_;
    FilterState cur_;
    int64_t altitude_utime_ = -1;
    double altitude_m_ = -1, altitude_depth_m_ = 0;     // the reading, and the depth it was taken at
    History hist_;
    FilterStats stats_;
};

}  // namespace nav

#endif

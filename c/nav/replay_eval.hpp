// Scoring an estimate against ground truth (the replay's evaluation): errors,
// distance travelled, normalised estimation error squared (NEES) and the time
// the filter spent trusted, degraded or invalid.
#ifndef NAV_REPLAY_EVAL_HPP
#define NAV_REPLAY_EVAL_HPP

#include <cstdint>
#include <cstdio>

extern "C" {
#include "auv/auv_ground_truth_t.h"
}

#include "nav/ekf_state.hpp"
#include "nav/nav_status.hpp"

namespace nav {

struct Running {
    double sum = 0, sum2 = 0, max = 0;
    uint64_t n = 0;
    void add(double v)
    {
        sum += v;
        sum2 += v * v;
        max = n == 0 || v > max ? v : max;
        n++;
    }
    double mean() const { return n ? sum / static_cast<double>(n) : 0; }
};

class Evaluator {
public:
    // Samples before score_from_s [sim s] are written to the CSV but neither
    // scored nor counted as distance travelled (e.g. the surface run before a dive).
    Evaluator(FILE *csv, double score_from_s);
    // One truth sample against the estimate at the same time.
    void add(const auv_ground_truth_t &truth, const FilterState &est, const NavStatus &st, double altitude_m);
    void print_summary(FILE *out) const;

private:
    FILE *csv_;
    double score_from_s_;
    bool have_last_ = false;
    double last_n_ = 0, last_e_ = 0;
    double distance_m_ = 0;
    double first_t_ = -1, last_t_ = 0, align_t_ = -1;
    Running h_err_, alt_err_, nees_pos_, nees_psi_, nees_vel_, nees_depth_, psi_err_;
    double final_h_err_ = 0, max_pct_ = 0;
    uint64_t alt_unknown_ = 0, samples_ = 0, aligned_ = 0, trusted_ = 0, degraded_ = 0, invalid_ = 0;
};

}  // namespace nav

#endif

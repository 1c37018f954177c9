// The front model the on-board estimator fits (docs/sampling.md, "The ocean's
// fields" and "The on-board front estimator"): the upper water's temperature
// across a front between two water masses, with an optional standing meander.
//
//   s = n cos(angle) + e sin(angle)             along the front
//   r = -n sin(angle) + e cos(angle)            across it, to its right
//   x = r - offset - A sin(2 pi s / L + phase)
//   T = Ta + (Tb - Ta) (1 + tanh(x / width)) / 2
//
// The fit works on q = [offset, angle, Ta, Tb, ln width (, A, ln L, phase)]:
// the logarithms keep width and wavelength positive and the steps in them
// relative. The same field is described by (angle + pi, -offset, Tb, Ta) and
// by (-A, phase + pi): canonical() picks angle in [-pi/2, pi/2), A >= 0,
// phase in [0, 2 pi).
#ifndef FRONTEST_FRONT_MODEL_HPP
#define FRONTEST_FRONT_MODEL_HPP

#include <cstdint>

#include <Eigen/Dense>

namespace frontest {

enum Param { OFFSET = 0, ANGLE, TA, TB, LOG_WIDTH, AMPLITUDE, LOG_WAVELENGTH, PHASE, kMeanderParams };
constexpr int kStraightParams = AMPLITUDE;  // 5: a straight front

// A temperature at a place: a bin of readings (the mean of `readings` CTD
// readings), or one synthetic sample in the tests.
struct Sample {
    double north_m = 0, east_m = 0, temperature_c = 0;
    int64_t utime = 0;
    int readings = 1;
};

// The front's parameters in the units of front_estimate_t.
struct Front {
    double offset_m = 0, angle_rad = 0, ta_c = 0, tb_c = 0, width_m = 1;
    bool meander = false;
    double amplitude_m = 0, wavelength_m = 0, phase_rad = 0;
};

using Vec = Eigen::VectorXd;

// q of a front (5 or 8 entries: f.meander), and back.
Vec to_q(const Front &f);
Front from_q(const Vec &q);
// The same field, in the canonical form (above).
Front canonical(Front f);

// Along and across the front of direction `angle` (s, r above).
void front_frame(double angle, double n, double e, double &s, double &r);

// T at (n, e) for q (5 or 8 entries); with grad (q.size() entries), dT/dq too.
double model(const Vec &q, double n, double e, double *grad = nullptr);

}  // namespace frontest

#endif

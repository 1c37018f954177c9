// The front's parameters by nonlinear least squares (Levenberg-Marquardt) on
// the model of front_model.hpp, with the covariance of the parameters from
// the fit, (J^T J)^-1 sigma^2, sigma^2 the residuals' variance. Pure: no LCM,
// no clock (the unit tests drive it with synthetic data).
//
// The fit, in order (docs/sampling.md, "The on-board front estimator"):
//  1. TOO_FEW unless there are min_samples samples whose temperatures span
//     min_contrast_c (5th to 95th percentile): both waters must have been seen.
//  2. Starts: the direction of the front on a 5-degree grid over half a
//     turn, each with the waters' temperatures from the samples on either
//     side, the offset where the temperature is half-way, a width from how
//     far across that half-way band spreads; the three best by residual, and
//     the last estimate (warm start). Levenberg-Marquardt from each on the
//     straight front (5 parameters); the lowest residual wins.
//  3. The meander (3 more parameters), from 12 starts (3 wavelengths, 4
//     phases) around the straight fit, only when the samples near the front
//     span meander_span_m along it; kept only if it is significant: an F
//     statistic over meander_f, an amplitude over 3 of its sigmas and a
//     wavelength the samples have seen half of.
//  4. DIVERGED when no start converged, the width left [min_width_m,
//     max_width_m] (no front in the data: a gradient, or a step no sample
//     lies in), or J^T J is singular (the data do not determine a parameter:
//     one straight pass across the front cannot tell its angle from its
//     width). Never an estimate with a NaN or an infinite sigma as OK.
#ifndef FRONTEST_FRONT_FIT_HPP
#define FRONTEST_FRONT_FIT_HPP

#include <limits>
#include <string>
#include <vector>

#include "frontest/front_model.hpp"

namespace frontest {

enum class Status { OK = 0, TOO_FEW = 1, DIVERGED = 2 };

struct FitOptions {
    int min_samples = 30;
    double min_contrast_c = 0.5;
    int max_iterations = 200;       // per start
    double min_width_m = 0.5;
    double max_width_m = 2000;
    double meander_span_m = 400;
    double meander_f = 10;
};

struct FitResult {
    Status status = Status::TOO_FEW;
    std::string text;
    Front front;                    // canonical (front_model.hpp)
    Front sigma;                    // 1-sigma of each field of front
    double rms_c = std::numeric_limits<double>::quiet_NaN();
    int iterations = 0;             // of the winning start
    int n = 0;                      // samples
};

// A teammate's estimate of the straight front (its summary over the team
// link) with its sigmas: fitted as a prior, one residual (q_k - p_k) / sigma_k
// per parameter beside the samples' (T - model) / data_sigma_c. With priors
// the TOO_FEW checks are off (a vehicle that has seen one water, or none,
// takes its teammates' estimate), the samples' residuals are scaled by
// data_sigma_c (their own fit's rms) and the covariance is (J^T J)^-1. The
// summaries must come from the teammates' own samples only, or an estimate
// would count itself again through them.
struct Prior {
    Front front, sigma;
};

FitResult fit_front(const std::vector<Sample> &samples, const FitOptions &opt, const Front *warm = nullptr,
                    const std::vector<Prior> &priors = {}, double data_sigma_c = 0.0);

const char *status_name(Status s);

}  // namespace frontest

#endif

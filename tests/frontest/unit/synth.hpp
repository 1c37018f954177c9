// Synthetic CTD samples from the estimator's own model (front_model.hpp) along
// a zig-zag across the front, with Gaussian noise from a fixed-seed generator
// (std::mt19937 is the same sequence everywhere; the Gaussian is our own
// Box-Muller, not the library's unspecified one).
#ifndef FRONTEST_SYNTH_HPP
#define FRONTEST_SYNTH_HPP

#include <cstdint>
#include <random>
#include <vector>

#include "frontest/front_model.hpp"

namespace synth {

struct Noise {
    std::mt19937 rng;
    explicit Noise(uint32_t seed) : rng(seed) {}
    double uniform() { return (static_cast<double>(rng()) + 0.5) / 4294967296.0; }
    double gauss();
};

// A zig-zag along the front f (straight part): legs at +-leg_angle to it,
// reaching `reach` metres either side of the front line at offset, from
// along-front s0 for `length` metres along it, a sample every `step` metres,
// each T from the model plus sigma_c of noise.
std::vector<frontest::Sample> zigzag(const frontest::Front &f, double s0, double length, double reach,
                                     double leg_angle, double step, double sigma_c, uint32_t seed);

}  // namespace synth

#endif

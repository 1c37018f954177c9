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

constexpr double kPi = 3.141592653589793;

// The tests' straight front: 300 m to the right of the origin at 0.2 rad, 16 C
// water on its left, 12 C on its right, 20 m wide.
inline frontest::Front straight_front()
{
    frontest::Front f;
    f.offset_m = 300;
    f.angle_rad = 0.2;
    f.ta_c = 16;
    f.tb_c = 12;
    f.width_m = 20;
    return f;
}

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

// The fit on synthetic data from its own model (synth.hpp): it recovers the
// parameters within their stated sigmas, the sigmas are honest over many
// noise draws, the meander is fitted only where the data support it, and a
// degenerate data set gives TOO_FEW or DIVERGED, never an OK with a NaN.
#include <cmath>
#include <cstdio>

#include "../../harness/unit.h"
#include "frontest/front_fit.hpp"
#include "synth.hpp"

using frontest::Front;
using frontest::Status;

namespace {

using synth::kPi;

// |estimate - truth| in sigmas, per field (angle and phase the short way round)
struct Z {
    double offset, angle, ta, tb, width, amplitude, wavelength, phase;
};

Z zscores(const frontest::FitResult &r, const Front &t)
{
    const Front &e = r.front, &s = r.sigma;
    Z z{};
    z.offset = (e.offset_m - t.offset_m) / s.offset_m;
    z.angle = std::remainder(e.angle_rad - t.angle_rad, 2 * kPi) / s.angle_rad;
    z.ta = (e.ta_c - t.ta_c) / s.ta_c;
    z.tb = (e.tb_c - t.tb_c) / s.tb_c;
    z.width = (e.width_m - t.width_m) / s.width_m;
    if (e.meander) {
        z.amplitude = (e.amplitude_m - t.amplitude_m) / s.amplitude_m;
        z.wavelength = (e.wavelength_m - t.wavelength_m) / s.wavelength_m;
        z.phase = std::remainder(e.phase_rad - t.phase_rad, 2 * kPi) / s.phase_rad;
    }
    return z;
}

void print(const char *what, const frontest::FitResult &r, const Front &t)
{
    const Front &e = r.front, &s = r.sigma;
    std::printf("# %s: %s (%s), %d iterations\n", what, frontest::status_name(r.status), r.text.c_str(), r.iterations);
    std::printf("#   offset %.2f +- %.2f m (true %.1f), angle %.4f +- %.4f rad (%.3f), Ta %.3f +- %.3f (%.1f), "
                "Tb %.3f +- %.3f (%.1f), width %.2f +- %.2f m (%.1f)\n",
                e.offset_m, s.offset_m, t.offset_m, e.angle_rad, s.angle_rad, t.angle_rad, e.ta_c, s.ta_c, t.ta_c,
                e.tb_c, s.tb_c, t.tb_c, e.width_m, s.width_m, t.width_m);
    if (e.meander)
        std::printf("#   amplitude %.2f +- %.2f m (%.1f), wavelength %.1f +- %.1f m (%.0f), phase %.3f +- %.3f rad "
                    "(%.3f)\n",
                    e.amplitude_m, s.amplitude_m, t.amplitude_m, e.wavelength_m, s.wavelength_m, t.wavelength_m,
                    e.phase_rad, s.phase_rad, t.phase_rad);
}

}  // namespace

TEST(model_gradient_matches_finite_differences)
{
    Front f = synth::straight_front();
    f.meander = true;
    f.amplitude_m = 30;
    f.wavelength_m = 500;
    f.phase_rad = 1.0;
    const frontest::Vec q = frontest::to_q(f);
    for (double n : {-50.0, 0.0, 120.0})
        for (double e : {280.0, 300.0, 320.0, 350.0}) {
            double g[frontest::kMeanderParams];
            frontest::model(q, n, e, g);
            for (int k = 0; k < frontest::kMeanderParams; k++) {
                frontest::Vec a = q, b = q;
                const double h = 1e-6 * (1 + std::fabs(q[k]));
                a[k] += h;
                b[k] -= h;
                const double fd = (frontest::model(a, n, e) - frontest::model(b, n, e)) / (2 * h);
                CHECK_NEAR(g[k], fd, 1e-6 * (1 + std::fabs(fd)));
            }
        }
}

TEST(canonical_form_is_the_same_field)
{
    for (double angle : {-3.0, -1.2, 0.0, 1.0, 1.7, 2.9, 4.5})
        for (int meander = 0; meander < 2; meander++) {
            Front f = synth::straight_front();
            f.angle_rad = angle;
            f.meander = meander;
            f.amplitude_m = -25;
            f.wavelength_m = 700;
            f.phase_rad = 5.5;
            const Front c = frontest::canonical(f);
            CHECK(c.angle_rad >= -kPi / 2 && c.angle_rad < kPi / 2);
            if (meander)
                CHECK(c.amplitude_m >= 0 && c.phase_rad >= 0 && c.phase_rad < 2 * kPi);
            const frontest::Vec a = frontest::to_q(f), b = frontest::to_q(c);
            for (double n = -400; n <= 400; n += 97)
                for (double e = -400; e <= 400; e += 89)
                    CHECK_NEAR(frontest::model(a, n, e), frontest::model(b, n, e), 1e-9);
        }
}

TEST(straight_front_recovered_within_its_sigmas)
{
    const Front t = synth::straight_front();
    // legs at 60 degrees to the front, 60 m either side, over 300 m along it: 8 crossings
    const auto xs = synth::zigzag(t, -150, 300, 60, 60 * kPi / 180, 1.0, 0.02, 1);
    const frontest::FitResult r = frontest::fit_front(xs, frontest::FitOptions{});
    print("straight front, 0.02 degC noise", r, t);
    CHECK(r.status == Status::OK);
    CHECK(!r.front.meander);
    CHECK_HAS(r.text.c_str(), "meander not fitted");
    const Z z = zscores(r, t);
    for (double v : {z.offset, z.angle, z.ta, z.tb, z.width})
        CHECK(std::fabs(v) < 3);
    CHECK(r.sigma.offset_m < 0.5 && r.sigma.angle_rad < 0.01 && r.sigma.width_m < 0.5);
    CHECK_NEAR(r.rms_c, 0.02, 0.003);
    // a warm start from the answer gives the same answer
    const frontest::FitResult w = frontest::fit_front(xs, frontest::FitOptions{}, &r.front);
    CHECK(w.status == Status::OK);
    CHECK_NEAR(w.front.offset_m, r.front.offset_m, 1e-6);
}

TEST(sigmas_are_honest_over_noise_draws)
{
    // 40 draws of the noise: each parameter within 2 of its sigmas about 95 % of the time
    const Front t = synth::straight_front();
    int within[5] = {0}, runs = 40;
    double worst = 0;
    for (int k = 0; k < runs; k++) {
        const auto xs = synth::zigzag(t, -150, 300, 60, 60 * kPi / 180, 2.0, 0.05, 100 + (uint32_t)k);
        const frontest::FitResult r = frontest::fit_front(xs, frontest::FitOptions{});
        CHECK(r.status == Status::OK);
        const Z z = zscores(r, t);
        const double v[5] = {z.offset, z.angle, z.ta, z.tb, z.width};
        for (int i = 0; i < 5; i++) {
            within[i] += std::fabs(v[i]) < 2;
            worst = std::fmax(worst, std::fabs(v[i]));
        }
    }
    std::printf("# within 2 sigma of %d draws: offset %d, angle %d, Ta %d, Tb %d, width %d; worst %.2f sigma\n", runs,
                within[0], within[1], within[2], within[3], within[4], worst);
    for (int i = 0; i < 5; i++)
        CHECK(within[i] >= 33); // 95 % of 40 is 38; binomial 1 % tail at 33
    CHECK(worst < 4.5);
}

TEST(meandering_front_recovered_where_the_data_span_it)
{
    Front t = synth::straight_front();
    t.meander = true;
    t.amplitude_m = 40;
    t.wavelength_m = 600;
    t.phase_rad = 1.0;
    // 1500 m along the front (2.5 wavelengths), 100 m either side of its line
    const auto xs = synth::zigzag(t, -750, 1500, 100, 60 * kPi / 180, 2.0, 0.02, 7);
    const frontest::FitResult r = frontest::fit_front(xs, frontest::FitOptions{});
    print("meandering front", r, t);
    CHECK(r.status == Status::OK);
    CHECK(r.front.meander);
    const Z z = zscores(r, t);
    for (double v : {z.offset, z.angle, z.ta, z.tb, z.width, z.amplitude, z.wavelength, z.phase})
        CHECK(std::fabs(v) < 3);
    // the same front seen over 300 m: a straight line is all the data support
    const auto few = synth::zigzag(t, -150, 300, 100, 60 * kPi / 180, 2.0, 0.02, 8);
    const frontest::FitResult s = frontest::fit_front(few, frontest::FitOptions{});
    std::printf("# meandering front over 300 m: %s: %s\n", frontest::status_name(s.status), s.text.c_str());
    CHECK(s.status == Status::OK && !s.front.meander);
}

TEST(too_few_or_one_water_is_too_few)
{
    const Front t = synth::straight_front();
    auto xs = synth::zigzag(t, -150, 300, 60, 60 * kPi / 180, 1.0, 0.02, 1);
    std::vector<frontest::Sample> some(xs.begin(), xs.begin() + 20);
    frontest::FitResult r = frontest::fit_front(some, frontest::FitOptions{});
    CHECK(r.status == Status::TOO_FEW);
    CHECK_HAS(r.text.c_str(), "20 samples: the fit needs 30");
    CHECK(std::isnan(r.rms_c));
    // all of it in water a, 200 m west of the front
    std::vector<frontest::Sample> west;
    for (frontest::Sample x : xs) {
        x.east_m -= 400;
        x.temperature_c = frontest::model(frontest::to_q(t), x.north_m, x.east_m);
        west.push_back(x);
    }
    r = frontest::fit_front(west, frontest::FitOptions{});
    CHECK(r.status == Status::TOO_FEW);
    CHECK_HAS(r.text.c_str(), "one water only");
}

TEST(degenerate_data_diverge_never_ok)
{
    const Front t = synth::straight_front();
    const frontest::Vec q = frontest::to_q(t);
    // one straight pass across the front: its angle and its width cannot be told apart
    std::vector<frontest::Sample> line;
    synth::Noise noise(3);
    for (int k = 0; k < 200; k++) {
        frontest::Sample x;
        x.north_m = 10 + 0.3 * k;
        x.east_m = 200 + 1.0 * k;
        x.temperature_c = frontest::model(q, x.north_m, x.east_m) + 0.02 * noise.gauss();
        line.push_back(x);
    }
    frontest::FitResult r = frontest::fit_front(line, frontest::FitOptions{});
    std::printf("# one straight pass: %s: %s\n", frontest::status_name(r.status), r.text.c_str());
    CHECK(r.status == Status::DIVERGED);
    CHECK_HAS(r.text.c_str(), "do not determine");
    // a linear gradient, no front: the width runs away
    std::vector<frontest::Sample> ramp = synth::zigzag(t, -150, 300, 60, 60 * kPi / 180, 1.0, 0.0, 1);
    for (frontest::Sample &x : ramp)
        x.temperature_c = 14 + 0.01 * x.east_m;
    r = frontest::fit_front(ramp, frontest::FitOptions{});
    std::printf("# a linear gradient: %s: %s\n", frontest::status_name(r.status), r.text.c_str());
    CHECK(r.status == Status::DIVERGED);
    // a NaN among the samples (the intake drops them; the fit must not pass one on)
    std::vector<frontest::Sample> bad = synth::zigzag(t, -150, 300, 60, 60 * kPi / 180, 1.0, 0.02, 1);
    bad[100].temperature_c = std::nan("");
    r = frontest::fit_front(bad, frontest::FitOptions{});
    std::printf("# a NaN sample: %s: %s\n", frontest::status_name(r.status), r.text.c_str());
    CHECK(r.status == Status::DIVERGED);
    CHECK_HAS(r.text.c_str(), "not a number");
    CHECK(std::isnan(r.rms_c));
}

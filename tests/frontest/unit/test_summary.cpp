// The front summary of the team link and a teammate's estimate as a prior:
// the summary fits its 16 bytes and, beside a status, the 32-byte frame; it
// comes back within half a step, its sigmas never smaller; and the fit takes
// teammates' summaries: a vehicle whose own samples cannot determine the
// front (one pass) or that has none gets the team's, and its own tighten it.
#include <cmath>
#include <cstdio>

#include "../../harness/unit.h"
#include "frontest/front_summary.hpp"
#include "synth.hpp"

using frontest::FitResult;
using frontest::Front;
using frontest::Status;

namespace {

using synth::kPi;

// A teammate's own fit: its zig-zag further along the front, sent and received.
frontest::Prior teammate(double s0, uint32_t seed, double noise_c = 0.05)
{
    const auto xs = synth::zigzag(synth::straight_front(), s0, 300, 60, 60 * kPi / 180, 2.0, noise_c, seed);
    const FitResult r = frontest::fit_front(xs, frontest::FitOptions{});
    team_msg_front m;
    CHECK(frontest::to_summary(r, 2, 1234.7, m));
    uint8_t frame[32] = {0};
    team_bits w;
    team_bits_writer(&w, frame, sizeof frame);
    CHECK(team_front_encode(&m, &w) == TEAM_OK);
    const auto got = frontest::fronts_in_frame(frame, team_bits_bytes(&w));
    CHECK(got.size() == 1);
    return frontest::from_summary(got.empty() ? m : got[0]);
}

std::vector<frontest::Sample> one_pass()
{
    const frontest::Vec q = frontest::to_q(synth::straight_front());
    std::vector<frontest::Sample> line;
    synth::Noise noise(3);
    for (int k = 0; k < 200; k++) {
        frontest::Sample x;
        x.north_m = 10 + 0.3 * k;
        x.east_m = 200 + 1.0 * k;
        x.temperature_c = frontest::model(q, x.north_m, x.east_m) + 0.02 * noise.gauss();
        line.push_back(x);
    }
    return line;
}

}  // namespace

TEST(summary_fits_its_bytes_and_the_frame)
{
    const auto xs = synth::zigzag(synth::straight_front(), -150, 300, 60, 60 * kPi / 180, 1.0, 0.02, 1);
    const FitResult r = frontest::fit_front(xs, frontest::FitOptions{});
    team_msg_front m;
    CHECK(frontest::to_summary(r, 3, 20000.0, m)); // mission time wraps at 16384 s
    CHECK(m.time_s == 20000 - 16384 && m.vehicle == 3 && m.samples == 600);
    CHECK(m.offset_sigma_m >= r.sigma.offset_m && m.angle_sigma >= r.sigma.angle_rad);
    CHECK(m.temp_sigma_c >= r.sigma.ta_c && m.temp_sigma_c >= r.sigma.tb_c && m.width_sigma_m >= r.sigma.width_m);
    // a status and a front in the team link's 32-byte frame (docs/team.md)
    uint8_t frame[32] = {0};
    team_bits w;
    team_bits_writer(&w, frame, sizeof frame);
    team_msg_status st = {1, 100, 10, 20, 5, 1.5, 1.5, 2, 1};
    CHECK(team_status_encode(&st, &w) == TEAM_OK);
    const size_t before = team_bits_bytes(&w);
    CHECK(team_front_encode(&m, &w) == TEAM_OK);
    std::printf("# status %zu bytes + front = %zu of 32 (front: %d bits)\n", before, team_bits_bytes(&w),
                TEAM_FRONT_BITS);
    CHECK(team_bits_bytes(&w) <= 32);
    CHECK(TEAM_FRONT_BITS <= 8 * TEAM_FRONT_MAX_BYTES && TEAM_FRONT_MAX_BYTES == 16);
    bool bad = true;
    const auto got = frontest::fronts_in_frame(frame, team_bits_bytes(&w), &bad);
    CHECK(!bad && got.size() == 1);
    if (got.size() == 1) {
        const team_msg_front &g = got[0];
        CHECK(std::fabs(g.offset_m - r.front.offset_m) <= 0.25 + 1e-9);
        CHECK(std::fabs(g.angle - r.front.angle_rad) <= 0.0005 + 1e-9);
        CHECK(std::fabs(g.temp_a_c - r.front.ta_c) <= 0.005 + 1e-9 && std::fabs(g.temp_b_c - r.front.tb_c) <= 0.005 + 1e-9);
        CHECK(std::fabs(g.width_m - r.front.width_m) <= 0.05 + 1e-9);
        CHECK(g.offset_sigma_m >= r.sigma.offset_m && g.width_sigma_m >= r.sigma.width_m);
        const frontest::Prior p = frontest::from_summary(g);
        CHECK(p.sigma.offset_m > g.offset_sigma_m); // plus the quantisation
    }
    // not OK, or beyond the schema (a width of 500 m): nothing to send
    FitResult wide = r;
    wide.front.width_m = 500;
    CHECK(!frontest::to_summary(wide, 3, 0, m));
    FitResult none;
    CHECK(!frontest::to_summary(none, 3, 0, m));
}

TEST(teammates_summaries_rescue_and_tighten_the_fit)
{
    const Front t = synth::straight_front();
    const frontest::Prior peer = teammate(150, 21);
    // one straight pass alone cannot tell the angle from the width ...
    const auto line = one_pass();
    FitResult alone = frontest::fit_front(line, frontest::FitOptions{});
    CHECK(alone.status == Status::DIVERGED);
    // ... with a teammate's summary it can
    const FitResult fused = frontest::fit_front(line, frontest::FitOptions{}, nullptr, {peer}, 0.02);
    std::printf("# one pass + a teammate: %s (%s): offset %.2f +- %.2f, angle %.4f +- %.4f, width %.2f +- %.2f\n",
                frontest::status_name(fused.status), fused.text.c_str(), fused.front.offset_m, fused.sigma.offset_m,
                fused.front.angle_rad, fused.sigma.angle_rad, fused.front.width_m, fused.sigma.width_m);
    CHECK(fused.status == Status::OK);
    CHECK_HAS(fused.text.c_str(), "and 1 teammate's summary");
    CHECK(std::fabs(fused.front.offset_m - t.offset_m) < 3 * fused.sigma.offset_m + 0.3);
    CHECK(std::fabs(fused.front.angle_rad - t.angle_rad) < 3 * fused.sigma.angle_rad + 0.001);
    CHECK(std::fabs(fused.front.width_m - t.width_m) < 3 * fused.sigma.width_m + 0.1);
    // no samples at all (a vehicle that has not reached the front): the teammates' estimate
    const frontest::Prior other = teammate(-450, 22);
    const FitResult none = frontest::fit_front({}, frontest::FitOptions{}, nullptr, {peer, other}, 0.05);
    CHECK(none.status == Status::OK && none.n == 0 && none.rms_c == 0.0);
    CHECK_HAS(none.text.c_str(), "straight front from 2 teammates' summaries only");
    CHECK(none.sigma.offset_m < peer.sigma.offset_m); // two are better than one
    // its own good samples and a teammate's: tighter than either
    const auto own = synth::zigzag(t, -150, 300, 60, 60 * kPi / 180, 2.0, 0.05, 23);
    const FitResult mine = frontest::fit_front(own, frontest::FitOptions{});
    const FitResult both = frontest::fit_front(own, frontest::FitOptions{}, nullptr, {peer}, mine.rms_c);
    std::printf("# offset sigma: own %.3f m, teammate %.3f m, both %.3f m\n", mine.sigma.offset_m, peer.sigma.offset_m,
                both.sigma.offset_m);
    CHECK(both.status == Status::OK);
    CHECK(both.sigma.offset_m < mine.sigma.offset_m && both.sigma.offset_m < peer.sigma.offset_m);
    CHECK(std::fabs(both.front.offset_m - t.offset_m) < 3 * both.sigma.offset_m);
    // a summary in the other form of the same field (angle + pi) is the same prior
    frontest::Prior flipped = peer;
    flipped.front.angle_rad += kPi;
    flipped.front.offset_m = -flipped.front.offset_m;
    std::swap(flipped.front.ta_c, flipped.front.tb_c);
    const FitResult same = frontest::fit_front(own, frontest::FitOptions{}, nullptr, {flipped}, mine.rms_c);
    CHECK_NEAR(same.front.offset_m, both.front.offset_m, 1e-6);
    // a summary that is not a number is refused, not fitted
    frontest::Prior broken = peer;
    broken.front.offset_m = std::nan("");
    CHECK(frontest::fit_front(own, frontest::FitOptions{}, nullptr, {broken}, mine.rms_c).status == Status::DIVERGED);
}

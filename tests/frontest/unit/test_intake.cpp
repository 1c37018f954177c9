// The intake: readings placed at the navigation of their time, averaged in
// bins of path, and every reading not used counted by its reason.
#include <cmath>

#include "../../harness/unit.h"
#include "frontest/front_intake.hpp"

using frontest::Intake;
using frontest::IntakeOptions;

namespace {
constexpr int64_t S = 1000000;
}

TEST(readings_are_placed_at_the_navigation_of_their_time)
{
    IntakeOptions o;
    o.bin_m = 1.0;
    Intake in(o);
    // the vehicle runs east at 1 m/s; navigation at 10 Hz, the CTD at 16 Hz
    for (int k = 0; k <= 300; k++)
        in.nav(k * S / 10, 5.0, 0.1 * k, true);
    for (int k = 0; k < 16 * 29; k++)
        in.ctd(k * S / 16, 10.0 + 0.01 * (k / 16.0), 5.0, true);
    in.advance(30 * S);
    const auto xs = in.samples();
    CHECK(in.readings_used() == 16 * 29);
    CHECK(xs.size() >= 28 && xs.size() <= 30); // a bin a metre
    for (const auto &x : xs) {
        CHECK_NEAR(x.north_m, 5.0, 1e-9);
        // the bin's mean position is its mean time's, the temperature its mean reading's
        CHECK_NEAR(x.east_m, (double)x.utime / S, 1e-6);
        CHECK_NEAR(x.temperature_c, 10.0 + 0.01 * (double)x.utime / S, 1e-6);
    }
    const frontest::Drops &d = in.drops();
    CHECK(d.not_valid + d.out_of_range + d.no_position + d.too_old + d.below_layer + d.time_rule == 0);
}

TEST(readings_not_used_are_counted_by_reason)
{
    IntakeOptions o;
    o.max_age_s = 100;
    o.max_depth_m = 15;
    Intake in(o);
    for (int k = 0; k <= 100; k++)
        in.nav(k * S, 0.0, (double)k, true);
    in.advance(100 * S);
    in.ctd(50 * S, 12.0, 5.0, false);           // not valid
    in.ctd(51 * S, std::nan(""), 5.0, true);    // out of range
    in.ctd(52 * S, 99.0, 5.0, true);            // out of range
    in.ctd(53 * S, -5.0, 5.0, true);            // out of range
    in.ctd(54 * S, 12.0, std::nan(""), true);   // out of range (depth)
    in.ctd(55 * S, 12.0, 20.0, true);           // below the layer
    in.ctd(-1 * S, 12.0, 5.0, true);            // too old (the window is 100 s)
    in.ctd(150 * S, 12.0, 5.0, true);           // no navigation after 100 s: waits ...
    in.ctd(160 * S, 12.0, 5.0, true);
    in.nav(200 * S, 0, 0, false);               // a solution marked invalid is not a position
    in.advance(151 * S);
    CHECK(in.drops().no_position == 0);         // ... up to a second of the clock
    in.advance(162 * S);
    const frontest::Drops &d = in.drops();
    CHECK(d.not_valid == 1);
    CHECK(d.out_of_range == 4);
    CHECK(d.below_layer == 1);
    CHECK(d.too_old == 1);
    CHECK(d.no_position == 2);
    CHECK(in.readings_used() == 0);
    // a gap of more than 2 s in the navigation places nothing in it
    Intake gap(o);
    gap.nav(0, 0, 0, true);
    gap.nav(5 * S, 0, 5, true);
    gap.ctd(2 * S, 12.0, 5.0, true);
    gap.advance(5 * S);
    CHECK(gap.drops().no_position == 1 && gap.readings_used() == 0);
}

TEST(bins_age_out_of_the_window)
{
    IntakeOptions o;
    o.max_age_s = 10;
    Intake in(o);
    for (int k = 0; k <= 200; k++)
        in.nav(k * S / 10, 0.0, 0.15 * k, true);
    for (int k = 0; k < 20 * 16; k++)
        in.ctd(k * S / 16, 12.0, 5.0, true);
    in.advance(20 * S);
    // readings before 10 s are gone, counted as too old
    const auto xs = in.samples();
    CHECK(!xs.empty() && xs.front().utime >= 10 * S - S);
    CHECK(in.drops().too_old > 140 && in.drops().too_old + in.readings_used() == 20 * 16);
}

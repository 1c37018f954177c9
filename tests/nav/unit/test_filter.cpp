// The filter on synthetic data: alignment, time ordering, gating, resets,
// status and allocation.
#include <algorithm>
#include <cmath>
#include <vector>

#include "../../harness/unit.h"
#include "../../harness/unit_alloc.h"
#include "nav/nav_filter.hpp"
#include "nav/nav_status.hpp"
#include "synth.hpp"

using namespace nav;

static double h_err(const NavFilter &f, const Synth &s)
{
    const SynthTruth t = s.truth(static_cast<double>(f.state().utime) * 1e-6);
    return std::hypot(f.state().x(PN) - t.n, f.state().x(PE) - t.e);
}

TEST(alignment_waits_for_heading_and_position)
{
    NavConfig c = synth_config();
    NavFilter f(c);
    Synth s;
    s.gps_until_s = 1e9;
    std::vector<Measurement> ms = s.run(3, c);
    // depth and DVL first: neither aligns
    for (const Measurement &m : ms)
        if (m.sensor == SENSOR_DEPTH || m.sensor == SENSOR_DVL)
            f.push(m);
    CHECK(!f.state().aligned());
    NavStatus st = evaluate_status(f.state(), f.state().utime, c);
    CHECK((st.bits & STATUS_INVALID) && !(st.bits & STATUS_ALIGNED) && !st.trusted);
    NavFilter g(c);
    int pushed = 0;
    for (const Measurement &m : ms) {
        g.push(m);
        pushed++;
        if (m.sensor == SENSOR_GPS)
            break;
    }
    CHECK(g.state().heading_init && g.state().position_init && g.state().aligned());
    st = evaluate_status(g.state(), g.state().utime, c);
    CHECK((st.bits & STATUS_ALIGNED) && !(st.bits & STATUS_INVALID));
    CHECK(pushed <= 4);     // the first tick's AHRS, depth, DVL and GPS
    CHECK_NEAR(g.state().x(PSI), s.heading, 0.05);
}

TEST(late_measurement_gives_the_same_estimate_as_on_time)
{
    NavConfig c = synth_config();
    Synth s;
    s.gps_until_s = 30;
    s.lbl_period_s = 10;
    const std::vector<Measurement> ms = s.run(120, c);
    NavFilter on_time(c), late(c);
    for (const Measurement &m : ms)
        on_time.push(m);
    // the same stream with every LBL ping held back 2.5 s, as a receiver does
    std::vector<std::pair<double, Measurement>> arrival;
    for (const Measurement &m : ms)
        arrival.push_back({static_cast<double>(m.utime) * 1e-6 + (m.sensor == SENSOR_LBL ? 2.5 : 0.0), m});
    std::stable_sort(arrival.begin(), arrival.end(), [](auto &a, auto &b) { return a.first < b.first; });
    for (auto &a : arrival)
        late.push(a.second);
    CHECK(late.stats().out_of_order == 11);
    CHECK(late.stats().replayed > 11 * 80);
    CHECK(on_time.stats().out_of_order == 0);
    CHECK(late.state().utime == on_time.state().utime);
    CHECK((late.state().x - on_time.state().x).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((late.state().P - on_time.state().P).cwiseAbs().maxCoeff() < 1e-9);
    CHECK(late.stats().sensor[SENSOR_LBL].accepted == on_time.stats().sensor[SENSOR_LBL].accepted);
}

TEST(measurement_older_than_the_history_is_dropped_and_counted)
{
    NavConfig c = synth_config();
    c.history_s = 2;
    Synth s;
    s.gps_until_s = 1e9;
    NavFilter f(c);
    for (const Measurement &m : s.run(20, c))
        f.push(m);
    const Vec before = f.state().x;
    Measurement old = s.lbl_ping(5.0, c);
    f.push(old);
    CHECK(f.stats().sensor[SENSOR_LBL].too_old == 1);
    CHECK(f.state().x == before);
}

TEST(push_allocates_nothing)
{
    NavConfig c = synth_config();
    Synth s;
    s.gps_until_s = 30;
    s.lbl_period_s = 5;
    const std::vector<Measurement> ms = s.run(300, c);
    NavFilter f(c);
    for (size_t i = 0; i < 400; i++)       // warm up: the history ring fills
        f.push(ms[i]);
    FilterState est;
    const long before = unit_allocs;
    for (size_t i = 400; i < ms.size(); i++) {
        f.push(ms[i]);
        if (i % 7 == 0) {       // and a late one now and then: the replay path
            Measurement late = ms[i - 30];
            late.sensor = SENSOR_DEPTH;
            late.depth.depth_m = s.depth;
            f.push(late);
        }
        f.estimate_at(ms[i].utime + 50000, est);
        evaluate_status(est, ms[i].utime + 50000, c);
    }
    CHECK(unit_allocs == before);
    CHECK(f.stats().out_of_order > 1000);
    CHECK(h_err(f, s) < 5);
}

TEST(lbl_long_outlier_is_gated_and_good_replies_kept)
{
    NavConfig c = synth_config();
    Synth s;
    s.gps_until_s = 20;
    const std::vector<Measurement> ms = s.run(200, c);
    NavFilter f(c);
    int outliers = 0;
    for (const Measurement &m : ms) {
        f.push(m);
        const double t = static_cast<double>(m.utime) * 1e-6;
        if (m.sensor == SENSOR_AHRS && std::fmod(t, 10.0) == 0 && t > 20) {
            Measurement ping = s.lbl_ping(t, c);
            if (std::fmod(t, 30.0) == 0) {     // multipath: 40 m more on one reply
                ping.lbl.two_way_travel_s[outliers % 3] += 2 * 40.0 / s.sound_speed;
                outliers++;
            }
            f.push(ping);
        }
    }
    const SensorStats &l = f.stats().sensor[SENSOR_LBL];
    CHECK(outliers == 6);
    CHECK(l.rejected == 6);
    CHECK(l.accepted == 18 * 3 - 6);
    CHECK(l.resets == 0);
    CHECK(h_err(f, s) < 2.0);
}

TEST(gps_jump_is_rejected_then_trusted_after_repeated_fixes)
{
    NavConfig c = synth_config();
    Synth s;
    s.gps_until_s = 1e9;
    NavFilter f(c);
    std::vector<Measurement> ms = s.run(60, c);
    int fixes = 0;
    for (Measurement m : ms) {
        if (m.sensor == SENSOR_GPS && m.utime > 30000000) {
            m.gps.north_m += 100;           // the receiver now disagrees by 100 m
            fixes++;
        }
        f.push(m);
        if (fixes == c.reset_after[SENSOR_GPS] - 1 && m.sensor == SENSOR_GPS) {
            CHECK(f.stats().sensor[SENSOR_GPS].rejected == static_cast<uint64_t>(fixes));
            CHECK(h_err(f, s) < 3);         // the jump has not moved the estimate
        }
    }
    CHECK(f.stats().sensor[SENSOR_GPS].resets == 1);
    // after the reset the estimate follows the (shifted) fixes
    const SynthTruth t = s.truth(60);
    CHECK_NEAR(f.state().x(PN) - t.n, 100, 5);
}

TEST(dvl_dropout_degrades_and_silence_invalidates)
{
    NavConfig c = synth_config();
    Synth s;
    s.gps_until_s = 10;
    s.lbl_period_s = 10;
    NavFilter f(c);
    for (const Measurement &m : s.run(200, c)) {
        const double t = static_cast<double>(m.utime) * 1e-6;
        if (m.sensor == SENSOR_DVL && t > 100 && t < 150)
            continue;   // DVL lost for 50 s
        f.push(m);
        if (m.sensor == SENSOR_AHRS && (t == 99 || t == 120 || t == 149 || t == 199)) {
            const NavStatus st = evaluate_status(f.state(), m.utime, c);
            const bool expect_degraded = t == 120 || t == 149;
            CHECK(((st.bits & STATUS_DEGRADED) != 0) == expect_degraded);
            CHECK(st.trusted == !expect_degraded);
            CHECK(!(st.bits & STATUS_INVALID));
            CHECK(h_err(f, s) < 5);
        }
    }
    FilterState est;
    f.estimate_at(f.state().utime + 3000000, est);     // 3 s of silence
    const NavStatus st = evaluate_status(est, est.utime, c);
    CHECK((st.bits & STATUS_INVALID) && !st.trusted);
}

TEST(heading_wraps_through_north)
{
    NavConfig c = synth_config();
    Synth s;
    s.heading = -0.2;
    s.turn_rate = 0.02;     // crosses north after 10 s
    s.gps_until_s = 1e9;
    NavFilter f(c);
    double worst = 0;
    for (const Measurement &m : s.run(30, c)) {
        f.push(m);
        const SynthTruth t = s.truth(static_cast<double>(m.utime) * 1e-6);
        worst = std::max(worst, std::fabs(wrap_pi(f.state().x(PSI) - t.psi)));
        CHECK(f.state().x(PSI) >= 0 && f.state().x(PSI) < 2 * M_PI);
    }
    CHECK(worst < 0.05);
    CHECK(f.stats().sensor[SENSOR_AHRS].rejected < 5);
}

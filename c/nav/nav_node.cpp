#include "nav/nav_node.hpp"

#include <cstdio>
#include <cstring>
#include <ctime>
#include <unistd.h>

extern "C" {
#include "auv/auv_lockstep_t.h"
#include "auv/auv_process_health_t.h"
#include "auv/auv_sim_clock_t.h"
}

namespace nav {

namespace {

double clock_s(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

// lockstep_t's encoding: fingerprint (8 bytes), utime (8), then the
// participant: its length with the NUL (4, big-endian), the characters, NUL.
constexpr int kParticipantAt = 16;

std::string lockstep_participant_field(const std::string &name)
{
    const uint32_t len = (uint32_t)name.size() + 1;
    std::string f{(char)(len >> 24), (char)(len >> 16), (char)(len >> 8), (char)len};
    f += name;
    f.push_back('\0');
    return f;
}

}  // namespace

NavNode::NavNode(const NodeOptions &opt, const NavConfig &cfg, lcm_t *lcm)
    : opt_(opt), lcm_(lcm), filter_(cfg), vehicle_(opt.vehicle)
{
    if (opt_.channel.empty())
        opt_.channel = opt_.vehicle + ".NAV";
    if (opt_.status_channel.empty())
        opt_.status_channel = opt_.vehicle + ".NAV_STATUS";
    wall_s_at_health_ = clock_s(CLOCK_MONOTONIC);
    cpu_s_at_health_ = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    tp_clock_init(&clock_, opt_.max_clock_jump_us);
    mgr_lockstep_init(&lockstep_, opt_.vehicle.c_str(), "NAV");
    sim_participant_ = opt_.vehicle + ".sim";
}

NavNode::~NavNode()
{
    for (rx_sub_t *s : subs_)
        rx_unsubscribe(lcm_, s);
    rx_unsubscribe(lcm_, clock_sub_);
    rx_unsubscribe(lcm_, altimeter_sub_);
    if (lockstep_sub_)
        rx_unsubscribe_raw(lcm_, lockstep_sub_);
}

bool NavNode::subscribe()
{
    for (int k = 0; k < kSensors; k++) {
        const SensorChannel &sc = kSensorChannels[k];
        ctx_[k] = {this, sc.sensor};
        const std::string ch = opt_.vehicle + "." + sc.topic;
        subs_[k] = rx_subscribe(lcm_, ch.c_str(), auv_type_find(sc.type), on_sensor, &ctx_[k]);
        if (!subs_[k])
            return false;
        // A burst (an LBL reply, a scheduling hiccup) must not overflow the
        // default 30-message queue and lose sensor data.
        rx_set_queue_capacity(subs_[k], 1000);
    }
    const std::string alt = opt_.vehicle + ".ALTIMETER";
    altimeter_sub_ = rx_subscribe(lcm_, alt.c_str(), auv_type_find("altimeter_t"), on_altimeter, this);
    if (!altimeter_sub_)
        return false;
    if (opt_.sim_clock) {
        clock_sub_ = rx_subscribe(lcm_, "SIM.CLOCK", auv_type_find("sim_clock_t"), on_clock, this);
        if (!clock_sub_)
            return false;
        rx_set_queue_capacity(clock_sub_, 1000);
        // Only its simulator's reports wake this process (the kernel's channel
        // filter compares the participant field, lcm_chanfilter.h): the
        // world's 5 reports per vehicle and step are O(N^2) otherwise.
        const std::string key = lockstep_participant_field(sim_participant_);
        lockstep_sub_ = rx_subscribe_raw_where(lcm_, "SIM.LOCKSTEP", key.data(), kParticipantAt, (int)key.size(),
                                               on_lockstep, this);
        if (!lockstep_sub_)
            return false;
        rx_raw_set_queue_capacity(lockstep_sub_, 1000);
    }
    return true;
}

void NavNode::on_sensor(const char *channel, const void *msg, int64_t, void *user)
{
    auto *ctx = static_cast<SubCtx *>(user);
    NavNode *n = ctx->node;
    Measurement m;
    // The time rule first: a stamp outside the valid range, ahead of the
    // mission clock by more than the tolerance (it would move the filter into
    // the future and make every honest measurement after it "too old") or
    // older than this sensor's newest is counted and dropped.
    const int64_t stamp = *static_cast<const int64_t *>(msg); // every sensor message starts with utime
    const tp_reason why = tp_input_offer(&n->order_[ctx->sensor], stamp, n->have_time_, n->now_us_,
                                         n->opt_.future_tol_us);
    if (why != TP_OK) {
        tp_count(&n->time_drops_, why, "auv-nav", channel, stamp);
        return;
    }
    Convert c = to_measurement(ctx->sensor, msg, n->opt_.vehicle.c_str(), m);
    switch (c) {
    case Convert::OK:
        n->filter_.push(m);
        n->attitude_fresh_ |= ctx->sensor == SENSOR_AHRS;
        break;
    case Convert::NOT_VALID: n->convert_.not_valid++; break;
    case Convert::WRONG_VEHICLE: n->convert_.wrong_vehicle++; break;
    case Convert::IMPLAUSIBLE: n->convert_.implausible++; break;
    }
}

void NavNode::on_altimeter(const char *channel, const void *msg, int64_t, void *user)
{
    auto *n = static_cast<NavNode *>(user);
    const int64_t stamp = *static_cast<const int64_t *>(msg);
    const tp_reason why = tp_input_offer(&n->alt_order_, stamp, n->have_time_, n->now_us_, n->opt_.future_tol_us);
    if (why != TP_OK) {
        tp_count(&n->time_drops_, why, "auv-nav", channel, stamp);
        return;
    }
    int64_t t = 0;
    const double a = altimeter_reading(msg, n->opt_.vehicle.c_str(), &t);
    if (a > 0)
        n->filter_.note_altitude(t, a);
}

void NavNode::on_clock(const char *, const void *msg, int64_t, void *user)
{
    auto *n = static_cast<NavNode *>(user);
    const auto *c = static_cast<const auv_sim_clock_t *>(msg);
    // Global time never runs backwards here and never leaps on one message;
    // a clock of an older election term (a server resumed after a freeze) is refused.
    const tp_reason old = tp_term_check(&n->clock_term_, c->term);
    if (old != TP_OK) {
        tp_count(&n->clock_drops_, old, "auv-nav", "SIM.CLOCK", c->utime);
        return;
    }
    if (n->clock_reading(c->utime, "SIM.CLOCK")) {
        tp_term_accept(&n->clock_term_, c->term);
        mgr_lockstep_on_clock(&n->lockstep_, n->lcm_, c);
    }
}

void NavNode::on_lockstep(const lcm_recv_buf_t *rbuf, const char *, void *user)
{
    // Every participant of the world reports each step here (5 per vehicle).
    // The channel filter lets only this vehicle's simulator's through, where
    // it is on; check anyway, and decode only that one (the layout: above).
    auto *n = static_cast<NavNode *>(user);
    const auto *d = static_cast<const uint8_t *>(rbuf->data);
    const std::string &me = n->sim_participant_;
    if (rbuf->data_size < 20 + me.size() + 1)
        return;
    const uint32_t len = (uint32_t)d[16] << 24 | (uint32_t)d[17] << 16 | (uint32_t)d[18] << 8 | d[19];
    if (len != me.size() + 1 || std::memcmp(d + 20, me.data(), me.size()) != 0)
        return;
    auv_lockstep_t m;
    if (auv_lockstep_t_decode(rbuf->data, 0, (int)rbuf->data_size, &m) < 0) {
        n->lockstep_decode_errors_++;
        return;
    }
    n->sim_seen_ = true;
    if (m.kind == AUV_LOCKSTEP_T_KIND_STEP_DONE && m.step > n->sim_done_)
        n->sim_done_ = m.step;
    auv_lockstep_t_decode_cleanup(&m);
}

void NavNode::lockstep_poll()
{
    if (!opt_.sim_clock)
        return;
    // The simulator sends a step's sensor data before its report of the step,
    // so its report here means all of them were handled (and their solutions
    // published, by the loop, right after each). A report repeated after a
    // loss is as good: it is keyed by step.
    if (lockstep_.pending_step >= 0 && sim_done_ < lockstep_.pending_step)
        return;
    mgr_lockstep_poll(&lockstep_, lcm_);
}

bool NavNode::step_data_in() const
{
    // a clock with no simulator in the lockstep (a test's, a replay's) has no data to wait for
    return !opt_.sim_clock || !sim_seen_ || lockstep_.pending_step < 0 || sim_done_ >= lockstep_.pending_step;
}

void NavNode::lockstep_leave()
{
    if (opt_.sim_clock)
        mgr_lockstep_leave(&lockstep_, lcm_);
}

bool NavNode::clock_reading(int64_t t, const char *source)
{
    const tp_reason why = tp_clock_offer(&clock_, t);
    if (why != TP_OK) {
        tp_count(&clock_drops_, why, "auv-nav", source, t);
        return false;
    }
    now_us_ = clock_.now;
    have_time_ = true;
    return true;
}

uint64_t NavNode::decode_errors() const
{
    uint64_t e = (clock_sub_ ? rx_decode_errors(clock_sub_) : 0) + (altimeter_sub_ ? rx_decode_errors(altimeter_sub_) : 0) +
                 lockstep_decode_errors_;
    for (const rx_sub_t *s : subs_)
        if (s)
            e += rx_decode_errors(s);
    return e;
}

void NavNode::publish_solution(int64_t t, const NavStatus &st)
{
    // Never a solution older than one already out: the managers' loops would
    // see time run backwards.
    if (!scratch_.aligned() || (published_ > 0 && t <= last_out_us_))
        return;
    last_out_us_ = t;
    auv_nav_solution_t sol;
    fill_solution(scratch_, st, filter_.config(), filter_.altitude_at(scratch_), &vehicle_[0], t, sol);
    auv_nav_solution_t_publish(lcm_, opt_.channel.c_str(), &sol);
    published_++;
}

void NavNode::publish_on_attitude()
{
    attitude_fresh_ = false;
    // At the time of the newest measurement, the compass's: no extrapolation.
    const int64_t t = filter_.state().utime;
    if (attitude_out_us_ > 0 && t > attitude_out_us_)
        attitude_interval_us_ = t - attitude_out_us_;
    attitude_out_us_ = t;
    filter_.estimate_at(t, scratch_);
    publish_solution(t, evaluate_status(scratch_, t, filter_.config()));
}

void NavNode::publish_cycle()
{
    // The solution is valid at the mission time, or at the newest
    // measurement if the clock lags it (never extrapolated backwards).
    const int64_t t = std::max(now_us_, filter_.state().utime);
    filter_.estimate_at(t, scratch_);
    const NavStatus st = evaluate_status(scratch_, t, filter_.config());
    // Each compass message already brings a solution out: the clock only
    // keeps them coming while the compass is silent (the status then says
    // why). Silent means: the other sensors' data have moved two compass
    // intervals past the last compass message, or the clock a whole second.
    // Not the clock alone: it runs up to a step ahead of the data, and
    // publishing on it would put a clock solution out before the compass's.
    const int64_t period_us = static_cast<int64_t>(1e6 / opt_.rate_hz);
    const int64_t silent_us = std::max(period_us, 2 * attitude_interval_us_);
    if (attitude_out_us_ == 0 || filter_.state().utime - attitude_out_us_ > silent_us ||
        now_us_ - attitude_out_us_ > 1000000)
        publish_solution(t, st);
    if (now_us_ >= next_status_us_) {
        auv_nav_filter_status_t fs;
        fill_filter_status(filter_, st, &vehicle_[0], t, fs, &time_drops_, &clock_drops_);
        auv_nav_filter_status_t_publish(lcm_, opt_.status_channel.c_str(), &fs);
        publish_health();
        next_status_us_ = now_us_ + 1000000;
    }
}

void NavNode::publish_health()
{
    const double wall = clock_s(CLOCK_MONOTONIC), cpu = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    auv_process_health_t h = {};
    h.utime = now_us_;
    h.vehicle = &vehicle_[0];
    h.process = const_cast<char *>("NAV");
    h.pid = static_cast<int32_t>(getpid());
    uint64_t received = 0;
    for (const rx_sub_t *s : subs_)
        if (s)
            received += rx_stats(s)->received;
    h.messages_received = static_cast<int64_t>(received);
    h.decode_errors = static_cast<int64_t>(decode_errors());
    h.cpu_load = wall > wall_s_at_health_ ? (cpu - cpu_s_at_health_) / (wall - wall_s_at_health_) : 0;
    wall_s_at_health_ = wall;
    cpu_s_at_health_ = cpu;
    auv_process_health_t_publish(lcm_, (opt_.vehicle + ".HEALTH").c_str(), &h);
}

void NavNode::print_summary() const
{
    const FilterStats &fs = filter_.stats();
    std::fprintf(stderr, "auv-nav: %llu solutions published; decode errors %llu; not valid %llu, wrong vehicle %llu, "
                         "implausible %llu; out of order %llu; numeric resets %llu\n",
                 (unsigned long long)published_, (unsigned long long)decode_errors(),
                 (unsigned long long)convert_.not_valid, (unsigned long long)convert_.wrong_vehicle,
                 (unsigned long long)convert_.implausible, (unsigned long long)fs.out_of_order,
                 (unsigned long long)fs.numeric_resets);
    std::fprintf(stderr, "auv-nav: time rule drops: invalid time %llu, from the future %llu, out of order %llu; "
                         "clock refused: invalid %llu, backwards %llu, unconfirmed jumps %llu, older term %llu\n",
                 (unsigned long long)time_drops_.n[TP_INVALID], (unsigned long long)time_drops_.n[TP_FUTURE],
                 (unsigned long long)time_drops_.n[TP_OUT_OF_ORDER], (unsigned long long)clock_drops_.n[TP_INVALID],
                 (unsigned long long)clock_drops_.n[TP_BACKWARDS], (unsigned long long)clock_drops_.n[TP_JUMP],
                 (unsigned long long)clock_drops_.n[TP_OLD_TERM]);
    for (int k = 0; k < kSensors; k++) {
        const SensorStats &s = fs.sensor[k];
        std::fprintf(stderr, "auv-nav:   %-5s %llu measurements, %llu accepted, %llu rejected, %llu resets, %llu too old\n",
                     sensor_name(k), (unsigned long long)s.measurements, (unsigned long long)s.accepted,
                     (unsigned long long)s.rejected, (unsigned long long)s.resets, (unsigned long long)s.too_old);
    }
}

}  // namespace nav

#include "frontest/front_node.hpp"

#include <cmath>
#include <cstdio>

extern "C" {
#include "auv/auv_ctd_t.h"
#include "auv/auv_front_estimate_t.h"
#include "auv/auv_modem_rx_t.h"
#include "auv/auv_nav_solution_t.h"
#include "auv/auv_sim_clock_t.h"
}

namespace frontest {

namespace {
// The samples' sigma beside teammates' summaries while the vehicle has no fit of
// its own to take it from: the CTD's 0.0005 degC is far below what the model
// misses of a real front; 0.05 degC lets neither side swamp the other.
constexpr double kDefaultDataSigmaC = 0.05;
constexpr int8_t kKindTeam = 2;  // modem_tx_t.KIND_TEAM
}  // namespace

static_assert(static_cast<int>(Status::OK) == AUV_FRONT_ESTIMATE_T_STATUS_OK &&
                  static_cast<int>(Status::TOO_FEW) == AUV_FRONT_ESTIMATE_T_STATUS_TOO_FEW &&
                  static_cast<int>(Status::DIVERGED) == AUV_FRONT_ESTIMATE_T_STATUS_DIVERGED,
              "status values differ from lcmtypes/front_estimate_t.lcm");

FrontNode::FrontNode(const NodeOptions &opt, lcm_t *lcm)
    : opt_(opt), lcm_(lcm), vehicle_(opt.vehicle), intake_(opt.intake)
{
    if (opt_.channel.empty())
        opt_.channel = opt_.vehicle + ".FRONT_ESTIMATE";
    if (opt_.team_channel.empty())
        opt_.team_channel = opt_.vehicle + ".FRONT_TEAM";
    tp_clock_init(&clock_, TP_MAX_CLOCK_JUMP_US);
}

FrontNode::~FrontNode()
{
    rx_unsubscribe(lcm_, ctd_sub_);
    rx_unsubscribe(lcm_, nav_sub_);
    rx_unsubscribe(lcm_, clock_sub_);
    rx_unsubscribe(lcm_, modem_sub_);
}

bool FrontNode::subscribe()
{
    const std::string ctd = opt_.vehicle + ".CTD", nav = opt_.vehicle + ".NAV";
    ctd_sub_ = rx_subscribe(lcm_, ctd.c_str(), auv_type_find("ctd_t"), on_ctd, this);
    nav_sub_ = rx_subscribe(lcm_, nav.c_str(), auv_type_find("nav_solution_t"), on_nav, this);
    const std::string modem = opt_.vehicle + ".MODEM_RX";
    modem_sub_ = rx_subscribe(lcm_, modem.c_str(), auv_type_find("modem_rx_t"), on_modem, this);
    if (!ctd_sub_ || !nav_sub_ || !modem_sub_)
        return false;
    // 16 Hz CTD and 20 Hz navigation between two fits: no burst may overflow liblcm's 30
    rx_set_queue_capacity(ctd_sub_, 1000);
    rx_set_queue_capacity(nav_sub_, 1000);
    if (opt_.sim_clock) {
        clock_sub_ = rx_subscribe(lcm_, "SIM.CLOCK", auv_type_find("sim_clock_t"), on_clock, this);
        if (!clock_sub_)
            return false;
        rx_set_queue_capacity(clock_sub_, 1000);
    }
    return true;
}

bool FrontNode::set_now(int64_t t)
{
    const tp_reason why = tp_clock_offer(&clock_, t);
    if (why != TP_OK) {
        tp_count(&clock_drops_, why, "auv-front-estimate", opt_.sim_clock ? "SIM.CLOCK" : "system clock", t);
        return false;
    }
    now_ = clock_.now;
    if (!have_time_)
        next_fit_ = now_;
    have_time_ = true;
    return true;
}

bool FrontNode::time_ok(tp_input &in, int64_t stamp, const char *channel)
{
    const tp_reason why = tp_input_offer(&in, stamp, have_time_, now_, TP_FUTURE_TOLERANCE_US);
    if (why == TP_OK)
        return true;
    tp_count(&time_drops_, why, "auv-front-estimate", channel, stamp);
    return false;
}

void FrontNode::on_ctd(const char *channel, const void *msg, int64_t, void *user)
{
    auto *n = static_cast<FrontNode *>(user);
    const auto *m = static_cast<const auv_ctd_t *>(msg);
    if (!n->time_ok(n->ctd_order_, m->utime, channel)) {
        n->intake_.count_time_rule();
        return;
    }
    n->intake_.ctd(m->utime, m->temperature_c, m->depth_m, m->valid);
}

void FrontNode::on_nav(const char *channel, const void *msg, int64_t, void *user)
{
    auto *n = static_cast<FrontNode *>(user);
    const auto *m = static_cast<const auv_nav_solution_t *>(msg);
    if (!n->time_ok(n->nav_order_, m->utime, channel))
        return;
    n->intake_.nav(m->utime, m->north_m, m->east_m, !(m->status & AUV_NAV_SOLUTION_T_STATUS_INVALID));
}

void FrontNode::on_clock(const char *, const void *msg, int64_t, void *user)
{
    auto *n = static_cast<FrontNode *>(user);
    const auto *c = static_cast<const auv_sim_clock_t *>(msg);
    const tp_reason old = tp_term_check(&n->term_, c->term);
    if (old != TP_OK) {
        tp_count(&n->clock_drops_, old, "auv-front-estimate", "SIM.CLOCK", c->utime);
        return;
    }
    if (n->set_now(c->utime))
        tp_term_accept(&n->term_, c->term);
}

void FrontNode::on_modem(const char *, const void *msg, int64_t, void *user)
{
    // a frame of the team link from a teammate: its front summaries (the other
    // messages are the navigator's team_link's business)
    auto *n = static_cast<FrontNode *>(user);
    const auto *m = static_cast<const auv_modem_rx_t *>(msg);
    if (m->kind != kKindTeam || !tp_utime_valid(m->utime) || n->opt_.vehicle == m->src_vehicle || m->n_bytes <= 0)
        return;
    bool bad = false;
    for (const team_msg_front &f : fronts_in_frame(m->payload, static_cast<size_t>(m->n_bytes), &bad)) {
        const std::string who = m->src_vehicle;
        if (!n->peers_.count(who))
            std::fprintf(stderr, "auv-front-estimate: %s: a front summary from %s (offset %.1f m, angle %.3f rad)\n",
                         n->opt_.vehicle.c_str(), who.c_str(), f.offset_m, f.angle);
        n->peers_[who] = Peer{m->utime, from_summary(f)};
        n->summaries_heard_++;
    }
    n->frames_bad_ += bad;
}

FitResult FrontNode::team_fit(const FitResult &own, const std::vector<Sample> &xs)
{
    const int64_t oldest = now_ - static_cast<int64_t>(opt_.intake.max_age_s * 1e6);
    for (auto it = peers_.begin(); it != peers_.end();) {
        if (it->second.heard < oldest) {
            std::fprintf(stderr, "auv-front-estimate: %s: %s's front summary is over %.0f s old: dropped\n",
                         opt_.vehicle.c_str(), it->first.c_str(), opt_.intake.max_age_s);
            it = peers_.erase(it);
        } else {
            ++it;
        }
    }
    if (peers_.empty())
        return own;
    std::vector<Prior> priors;
    for (const auto &p : peers_)
        priors.push_back(p.second.prior);
    const double sigma = own.status == Status::OK ? std::max(own.rms_c, 1e-3) : kDefaultDataSigmaC;
    return fit_front(xs, opt_.fit, have_team_ok_ ? &last_team_ok_ : nullptr, priors, sigma);
}

void FrontNode::cycle()
{
    if (!have_time_)
        return;
    intake_.advance(now_);
    if (now_ < next_fit_)
        return;
    next_fit_ = tp_sat_add(now_, static_cast<int64_t>(1e6 / opt_.rate_hz));
    const std::vector<Sample> xs = intake_.samples();
    const FitResult r = fit_front(xs, opt_.fit, have_ok_ ? &last_ok_ : nullptr);
    if (r.status == Status::OK) {
        last_ok_ = r.front;
        have_ok_ = true;
    }
    if (!logged_status_ || r.status != last_status_)
        std::fprintf(stderr, "auv-front-estimate: %s at %.1f s: %s: %s\n", opt_.vehicle.c_str(), (double)now_ / 1e6,
                     status_name(r.status), r.text.c_str());
    logged_status_ = true;
    last_status_ = r.status;
    publish(opt_.channel, r, xs, 0);
    const FitResult team = team_fit(r, xs);
    if (team.status == Status::OK) {
        last_team_ok_ = team.front;
        have_team_ok_ = true;
    }
    publish(opt_.team_channel, team, xs, static_cast<int>(peers_.size()));
}

void FrontNode::publish(const std::string &channel, const FitResult &r, const std::vector<Sample> &xs, int peers)
{
    const double nan = std::nan("");
    const bool ok = r.status == Status::OK;
    auv_front_estimate_t m = {};
    m.utime = now_;
    m.vehicle = &vehicle_[0];
    m.status = static_cast<int8_t>(r.status);
    std::string text = r.text;
    m.status_text = &text[0];
    const Front &f = r.front, &s = r.sigma;
    m.meander = ok && f.meander;
    auto v = [&](double x) { return ok ? x : nan; };
    m.offset_m = v(f.offset_m);
    m.angle_rad = v(f.angle_rad);
    m.temperature_a_c = v(f.ta_c);
    m.temperature_b_c = v(f.tb_c);
    m.width_m = v(f.width_m);
    m.amplitude_m = ok ? (f.meander ? f.amplitude_m : 0.0) : nan;
    m.wavelength_m = ok && f.meander ? f.wavelength_m : nan;
    m.phase_rad = ok && f.meander ? f.phase_rad : nan;
    m.offset_sigma_m = v(s.offset_m);
    m.angle_sigma_rad = v(s.angle_rad);
    m.temperature_a_sigma_c = v(s.ta_c);
    m.temperature_b_sigma_c = v(s.tb_c);
    m.width_sigma_m = v(s.width_m);
    m.amplitude_sigma_m = ok && f.meander ? s.amplitude_m : nan;
    m.wavelength_sigma_m = ok && f.meander ? s.wavelength_m : nan;
    m.phase_sigma_rad = ok && f.meander ? s.phase_rad : nan;
    m.peers_used = peers;
    m.residual_rms_c = v(r.rms_c);
    m.iterations = r.iterations;
    m.samples_used = static_cast<int32_t>(xs.size());
    m.readings_used = intake_.readings_used();
    m.first_utime = xs.empty() ? 0 : xs.front().utime;
    m.last_utime = xs.empty() ? 0 : xs.back().utime;
    const Drops &d = intake_.drops();
    m.dropped_not_valid = d.not_valid;
    m.dropped_out_of_range = d.out_of_range;
    m.dropped_no_position = d.no_position;
    m.dropped_too_old = d.too_old;
    m.dropped_below_layer = d.below_layer;
    m.dropped_time_rule = d.time_rule;
    auv_front_estimate_t_publish(lcm_, channel.c_str(), &m);
    published_++;
}

void FrontNode::print_summary() const
{
    const Drops &d = intake_.drops();
    std::fprintf(stderr,
                 "auv-front-estimate: %llu estimates published; readings used %lld; dropped: not valid %lld, out of "
                 "range %lld, no position %lld, too old %lld, below the layer %lld, time rule %lld; decode errors "
                 "%llu; teammates' summaries heard %llu, team frames that did not decode %llu\n",
                 (unsigned long long)published_, (long long)intake_.readings_used(), (long long)d.not_valid,
                 (long long)d.out_of_range, (long long)d.no_position, (long long)d.too_old, (long long)d.below_layer,
                 (long long)d.time_rule,
                 (unsigned long long)(rx_decode_errors(ctd_sub_) + rx_decode_errors(nav_sub_) +
                                      rx_decode_errors(modem_sub_) + (clock_sub_ ? rx_decode_errors(clock_sub_) : 0)),
                 (unsigned long long)summaries_heard_, (unsigned long long)frames_bad_);
}

}  // namespace frontest

#include "nav/nav_filter.hpp"

#include "nav/ekf_predict.hpp"

namespace nav {

NavFilter::NavFilter(const NavConfig &cfg, size_t history_capacity) : cfg_(cfg), hist_(history_capacity)
{
    init_state(cur_, cfg_);
    if (cfg_.have_initial_position) {   // the launch position: known before any fix
        const double v = cfg_.initial_position_sigma_m * cfg_.initial_position_sigma_m;
        reset_state(cur_, PN, cfg_.initial_north_m, v);
        reset_state(cur_, PE, cfg_.initial_east_m, v);
        cur_.position_init = true;
    }
}

void NavFilter::restart()
{
    const int64_t t = cur_.utime;
    init_state(cur_, cfg_);
    cur_.utime = t;
}

void NavFilter::apply(FilterState &s, const Measurement &m, Outcome *o) const
{
    predict(s, m.utime, cfg_);
    Outcome r;
    switch (m.sensor) {
    case SENSOR_AHRS: r = update_ahrs(s, m.ahrs, m.utime, cfg_); break;
    case SENSOR_DEPTH: r = update_depth(s, m.depth, m.utime, cfg_); break;
    case SENSOR_DVL: r = update_dvl(s, m.dvl, m.utime, cfg_); break;
    case SENSOR_GPS: r = update_gps(s, m.gps, m.utime, cfg_); break;
    case SENSOR_LBL: r = update_lbl(s, m.lbl, m.utime, cfg_); break;
    }
    if (o)
        *o = r;
}

Outcome NavFilter::push(const Measurement &m)
{
    Outcome o;
    if (m.sensor < 0 || m.sensor >= kSensors)
        return o;
    SensorStats &st = stats_.sensor[m.sensor];
    st.measurements++;
    if (m.sensor == SENSOR_DVL && m.dvl.altitude_m > 0)
        note_altitude(m.utime, m.dvl.altitude_m);
    if (cur_.utime < 0 || m.utime >= cur_.utime) {
        apply(cur_, m, &o);
        hist_.push_back(m, cur_);
    } else {
        stats_.out_of_order++;
        size_t i = hist_.count_at_or_before(m.utime);
        if (i == 0) {           // older than everything kept
            st.too_old++;
            return o;
        }
        FilterState s = hist_.at(i - 1).post;
        apply(s, m, &o);
        if (!hist_.insert(i, m, s)) {
            st.too_old++;
            return o;
        }
        for (size_t j = i + 1; j < hist_.size(); j++) {
            HistoryEntry &e = hist_.at(j);
            apply(s, e.m, nullptr);
            e.post = s;
            stats_.replayed++;
        }
        cur_ = s;
    }
    if (!cur_.x.allFinite() || !cur_.P.allFinite()) {
        // Should never happen with plausible inputs; if it does, a filter
        // stuck on NaN would be worse than one that aligns again.
        stats_.numeric_resets++;
        restart();
        while (hist_.size() > 0)
            hist_.pop_front();
        return o;
    }
    st.accepted += static_cast<uint64_t>(o.accepted);
    st.rejected += static_cast<uint64_t>(o.rejected);
    st.unknown += static_cast<uint64_t>(o.unknown);
    st.resets += o.reset ? 1 : 0;
    trim();
    return o;
}

void NavFilter::trim()
{
    const int64_t keep_from = cur_.utime - static_cast<int64_t>(cfg_.history_s * 1e6);
    while (hist_.size() > 1 && hist_.at(0).m.utime < keep_from)
        hist_.pop_front();
}

void NavFilter::note_altitude(int64_t utime, double altitude_m)
{
    if (!(altitude_m > 0) || utime < altitude_utime_)
        return;
    altitude_utime_ = utime;
    altitude_m_ = altitude_m;
    altitude_depth_m_ = cur_.depth_init ? cur_.x(PD) : 0.0;
}

double NavFilter::altitude_at(const FilterState &est) const
{
    if (altitude_utime_ < 0 || static_cast<double>(est.utime - altitude_utime_) * 1e-6 > cfg_.altitude_timeout_s)
        return -1.0;
    const double a = altitude_m_ - (est.depth_init ? est.x(PD) - altitude_depth_m_ : 0.0);
    return a > 0 ? a : 0.0;
}

void NavFilter::estimate_at(int64_t utime, FilterState &out) const
{
    out = cur_;
    if (utime > out.utime)
        predict(out, utime, cfg_);
}

}  // namespace nav

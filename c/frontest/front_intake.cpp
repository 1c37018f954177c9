#include "frontest/front_intake.hpp"

#include <algorithm>
#include <cmath>

namespace frontest {

namespace {
constexpr double kSeaMinC = -3.0, kSeaMaxC = 45.0;      // in-situ temperatures a sea holds
constexpr double kMinDepthM = -5.0, kMaxDepthM = 11000.0;
constexpr int64_t kNavKeepUs = 60000000;                // navigation kept for placing readings
int64_t us(double s) { return static_cast<int64_t>(s * 1e6); }
}  // namespace

void Intake::nav(int64_t t, double north_m, double east_m, bool usable)
{
    if (!usable || !std::isfinite(north_m) || !std::isfinite(east_m))
        return;
    if (!nav_.empty() && t <= nav_.back().t)
        return;
    nav_.push_back({t, north_m, east_m});
    while (nav_.size() > 2 && nav_.front().t < t - kNavKeepUs)
        nav_.pop_front();
}

void Intake::ctd(int64_t t, double temperature_c, double depth_m, bool valid)
{
    if (!valid) {
        drops_.not_valid++;
        return;
    }
    if (!(temperature_c >= kSeaMinC && temperature_c <= kSeaMaxC && depth_m >= kMinDepthM && depth_m <= kMaxDepthM)) {
        drops_.out_of_range++;
        return;
    }
    if (depth_m > opt_.max_depth_m) {
        drops_.below_layer++;
        return;
    }
    if (have_now_ && t < now_ - us(opt_.max_age_s)) {
        drops_.too_old++;
        return;
    }
    pending_.push_back({t, temperature_c});
}

void Intake::place(const Reading &r, double n, double e)
{
    Bin &b = open_;
    if (b.count > 0 && (std::hypot(n - b.first_n, e - b.first_e) >= opt_.bin_m || r.t - b.first_t > us(opt_.bin_max_s))) {
        bins_.push_back(b);
        b = Bin{};
        while (bins_.size() >= opt_.max_bins) {
            drops_.too_old += bins_.front().count;
            bins_.pop_front();
        }
    }
    if (b.count == 0) {
        b.first_n = n;
        b.first_e = e;
        b.first_t = r.t;
    }
    b.n += n;
    b.e += e;
    b.temp += r.temperature_c;
    b.t += static_cast<double>(r.t);
    b.last_t = r.t;
    b.count++;
}

void Intake::advance(int64_t now)
{
    have_now_ = true;
    now_ = std::max(now_, now);
    const int64_t wait = us(opt_.position_wait_s), gap = us(opt_.nav_gap_s);
    while (!pending_.empty()) {
        const Reading r = pending_.front();
        if (nav_.empty() || r.t > nav_.back().t) {
            if (now_ - r.t <= wait)
                break;  // its navigation may still come
            drops_.no_position++;
        } else if (r.t < nav_.front().t) {
            drops_.no_position++;
        } else {
            auto hi = std::lower_bound(nav_.begin(), nav_.end(), r.t,
                                       [](const NavPoint &p, int64_t t) { return p.t < t; });
            if (hi->t == r.t) {
                place(r, hi->n, hi->e);
            } else {
                auto lo = hi - 1;
                if (hi->t - lo->t > gap) {
                    drops_.no_position++;
                } else {
                    const double f = static_cast<double>(r.t - lo->t) / static_cast<double>(hi->t - lo->t);
                    place(r, lo->n + f * (hi->n - lo->n), lo->e + f * (hi->e - lo->e));
                }
            }
        }
        pending_.pop_front();
    }
    const int64_t oldest = now_ - us(opt_.max_age_s);
    while (!bins_.empty() && bins_.front().last_t < oldest) {
        drops_.too_old += bins_.front().count;
        bins_.pop_front();
    }
    if (open_.count > 0 && open_.last_t < oldest) {
        drops_.too_old += open_.count;
        open_ = Bin{};
    }
}

std::vector<Sample> Intake::samples() const
{
    std::vector<Sample> out;
    out.reserve(bins_.size() + 1);
    auto add = [&out](const Bin &b) {
        const double k = b.count;
        Sample s;
        s.north_m = b.n / k;
        s.east_m = b.e / k;
        s.temperature_c = b.temp / k;
        s.utime = static_cast<int64_t>(b.t / k);
        s.readings = b.count;
        out.push_back(s);
    };
    for (const Bin &b : bins_)
        add(b);
    if (open_.count > 0)
        add(open_);
    return out;
}

int64_t Intake::readings_used() const
{
    int64_t k = open_.count;
    for (const Bin &b : bins_)
        k += b.count;
    return k;
}

}  // namespace frontest

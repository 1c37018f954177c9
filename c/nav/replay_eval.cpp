#include "nav/replay_eval.hpp"

#include <cmath>

namespace nav {

namespace {

// Distance below which a percentage of distance travelled means little: the
// error of the fix the run starts from is still most of it.
constexpr double kMinDistanceForPct = 200.0;

}  // namespace

Evaluator::Evaluator(FILE *csv, double score_from_s) : csv_(csv), score_from_s_(score_from_s)
{
    if (csv_)
        std::fprintf(csv_, "t_s,true_n,true_e,true_d,true_psi,true_u,true_v,true_w,true_cn,true_ce,"
                           "est_n,est_e,est_d,est_psi,est_u,est_v,est_w,est_bias,est_cn,est_ce,"
                           "sd_n,sd_e,sd_d,sd_psi,status,trusted,h_err_m,distance_m,nees_pos,nees_psi,nees_vel\n");
}

void Evaluator::add(const auv_ground_truth_t &tr, const FilterState &s, const NavStatus &st, double altitude_m)
{
    const double t = static_cast<double>(tr.utime) * 1e-6;
    if (first_t_ < 0)
        first_t_ = t;
    last_t_ = t;
    const bool scored = t >= score_from_s_;
    if (have_last_ && scored)
        distance_m_ += std::hypot(tr.eta[0] - last_n_, tr.eta[1] - last_e_);
    last_n_ = tr.eta[0];
    last_e_ = tr.eta[1];
    have_last_ = true;
    samples_++;
    if (!s.aligned())
        return;
    if (align_t_ < 0)
        align_t_ = t;
    aligned_++;
    trusted_ += st.trusted;
    degraded_ += (st.bits & STATUS_DEGRADED) != 0;
    invalid_ += (st.bits & STATUS_INVALID) != 0;

    const Eigen::Vector2d ep(s.x(PN) - tr.eta[0], s.x(PE) - tr.eta[1]);
    const double h_err = ep.norm();
    const double nees_pos = ep.dot(s.P.block<2, 2>(PN, PN).ldlt().solve(ep));
    const double e_psi = wrap_pi(s.x(PSI) - tr.eta[5]);
    const double nees_psi = e_psi * e_psi / s.P(PSI, PSI);
    const Vec3 ev(s.x(VU) - tr.nu[0], s.x(VV) - tr.nu[1], s.x(VW) - tr.nu[2]);
    const double nees_vel = ev.dot(s.P.block<3, 3>(VU, VU).ldlt().solve(ev));
    const double e_d = s.x(PD) - tr.eta[2];
    if (csv_)
        std::fprintf(csv_, "%.3f,%.3f,%.3f,%.3f,%.5f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f,%.5f,%.4f,%.4f,%.4f,%.5f,%.4f,"
                           "%.4f,%.3f,%.3f,%.3f,%.5f,%d,%d,%.3f,%.2f,%.3f,%.3f,%.3f\n",
                     t, tr.eta[0], tr.eta[1], tr.eta[2], tr.eta[5], tr.nu[0], tr.nu[1], tr.nu[2],
                     tr.current_ned_mps[0], tr.current_ned_mps[1], s.x(PN), s.x(PE), s.x(PD), s.x(PSI), s.x(VU),
                     s.x(VV), s.x(VW), s.x(BIAS), s.x(CN), s.x(CE), std::sqrt(s.P(PN, PN)), std::sqrt(s.P(PE, PE)),
                     std::sqrt(s.P(PD, PD)), std::sqrt(s.P(PSI, PSI)), st.bits, st.trusted ? 1 : 0, h_err,
                     distance_m_, nees_pos, nees_psi, nees_vel);
    if (!scored)
        return;
    h_err_.add(h_err);
    if (altitude_m >= 0)
        alt_err_.add(std::fabs(altitude_m - tr.altitude_m));
    else
        alt_unknown_++;
    psi_err_.add(std::fabs(e_psi));
    nees_pos_.add(nees_pos);
    nees_psi_.add(nees_psi);
    nees_vel_.add(nees_vel);
    nees_depth_.add(e_d * e_d / s.P(PD, PD));
    final_h_err_ = h_err;
    if (distance_m_ >= kMinDistanceForPct)
        max_pct_ = std::max(max_pct_, 100.0 * h_err / distance_m_);
}

void Evaluator::print_summary(FILE *out) const
{
    const double a = aligned_ ? static_cast<double>(aligned_) : 1.0;
    std::fprintf(out, "duration_s %.2f\n", last_t_ - (first_t_ < 0 ? 0 : first_t_));
    std::fprintf(out, "truth_samples %llu\n", (unsigned long long)samples_);
    std::fprintf(out, "aligned_samples %llu\n", (unsigned long long)aligned_);
    std::fprintf(out, "align_time_s %.2f\n", align_t_ < 0 ? -1.0 : align_t_ - first_t_);
    std::fprintf(out, "distance_m %.2f\n", distance_m_);
    std::fprintf(out, "h_err_rms_m %.4f\n", aligned_ ? std::sqrt(h_err_.sum2 / a) : -1.0);
    std::fprintf(out, "h_err_max_m %.4f\n", h_err_.max);
    std::fprintf(out, "h_err_final_m %.4f\n", final_h_err_);
    std::fprintf(out, "h_err_final_pct %.4f\n", distance_m_ > 0 ? 100.0 * final_h_err_ / distance_m_ : -1.0);
    std::fprintf(out, "h_err_max_pct %.4f\n", max_pct_);
    std::fprintf(out, "altitude_err_mean_m %.4f\n", alt_err_.mean());
    std::fprintf(out, "altitude_unknown_fraction %.4f\n", static_cast<double>(alt_unknown_) / a);
    std::fprintf(out, "heading_err_mean_deg %.4f\n", psi_err_.mean() * 180.0 / M_PI);
    std::fprintf(out, "nees_pos_mean %.4f\n", nees_pos_.mean());
    std::fprintf(out, "nees_pos_max %.4f\n", nees_pos_.max);
    std::fprintf(out, "nees_heading_mean %.4f\n", nees_psi_.mean());
    std::fprintf(out, "nees_vel_mean %.4f\n", nees_vel_.mean());
    std::fprintf(out, "nees_depth_mean %.4f\n", nees_depth_.mean());
    std::fprintf(out, "trusted_fraction %.4f\n", static_cast<double>(trusted_) / a);
    std::fprintf(out, "degraded_fraction %.4f\n", static_cast<double>(degraded_) / a);
    std::fprintf(out, "invalid_fraction %.4f\n", static_cast<double>(invalid_) / a);
}

}  // namespace nav

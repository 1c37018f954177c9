#include "frontest/front_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace frontest {

namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const char *const kParamNames[kMeanderParams] = {"offset", "angle", "temperature a", "temperature b",
                                                 "width", "amplitude", "wavelength", "phase"};

struct Lm {
    Vec q;
    double rss = INFINITY;
    int iterations = 0;
    bool converged = false;
};

// The sigma of a prior on q[k] (on ln width: the width's relative sigma).
double prior_sigma(const Prior &p, int k)
{
    switch (k) {
    case OFFSET: return p.sigma.offset_m;
    case ANGLE: return p.sigma.angle_rad;
    case TA: return p.sigma.ta_c;
    case TB: return p.sigma.tb_c;
    default: return p.sigma.width_m / p.front.width_m;
    }
}

// The prior's form of its field (front_model.hpp, canonical()) whose angle is
// nearest `angle`: a prior is a distance in q, so it must be in the fit's form.
Prior aligned(Prior p, double angle)
{
    if (std::fabs(std::remainder(angle - p.front.angle_rad, 2 * kPi)) > kPi / 2) {
        p.front.angle_rad += kPi;
        p.front.offset_m = -p.front.offset_m;
        std::swap(p.front.ta_c, p.front.tb_c);
        std::swap(p.sigma.ta_c, p.sigma.tb_c);
    }
    p.front.angle_rad = angle - std::remainder(angle - p.front.angle_rad, 2 * kPi);
    p.front.meander = false;
    return p;
}

// What is fitted: the samples, each residual divided by data_sigma (1 when
// there are no priors: the residuals' own scale then sets sigma^2), and the
// priors, one row per straight parameter, (q_k - p_k) / sigma_k.
struct Problem {
    const std::vector<Sample> &xs;
    double data_sigma = 1.0;
    std::vector<Prior> priors;  // aligned to the start (align())
    Eigen::Index rows() const { return (Eigen::Index)(xs.size() + kStraightParams * priors.size()); }
};

// Residuals and, with J, the Jacobian; the sum of squares. Fixed sizes for
// the P parameters (5 or 8): Eigen's dynamic-size solvers trip GCC's
// maybe-uninitialized under -Werror.
template <int P>
double residuals(const Problem &pb, const Vec &q, Vec &r, Eigen::Matrix<double, Eigen::Dynamic, P> *J)
{
    double grad[kMeanderParams];
    double rss = 0;
    const double w = 1.0 / pb.data_sigma;
    Eigen::Index i = 0;
    for (const Sample &x : pb.xs) {
        const double m = model(q, x.north_m, x.east_m, J ? grad : nullptr);
        r[i] = (m - x.temperature_c) * w;
        rss += r[i] * r[i];
        if (J)
            for (int k = 0; k < P; k++)
                (*J)(i, k) = grad[k] * w;
        i++;
    }
    for (const Prior &p : pb.priors) {
        const Vec qp = to_q(p.front);
        for (int k = 0; k < kStraightParams; k++) {
            const double sd = prior_sigma(p, k);
            r[i] = (q[k] - qp[k]) / sd;
            rss += r[i] * r[i];
            if (J) {
                for (int j = 0; j < P; j++)
                    (*J)(i, j) = 0;
                (*J)(i, k) = 1 / sd;
            }
            i++;
        }
    }
    return rss;
}

double rss_of(const Problem &pb, const Vec &q)
{
    Vec r(pb.rows());
    return residuals<kStraightParams>(pb, q, r, nullptr);
}

// Levenberg-Marquardt (Marquardt's scaling: lambda times the diagonal of J^T J).
template <int P>
Lm levenberg_marquardt(const Problem &xs, Vec q, int max_iterations)
{
    using MatP = Eigen::Matrix<double, P, P>;
    using VecP = Eigen::Matrix<double, P, 1>;
    const Eigen::Index n = xs.rows();
    Vec r(n), r_new(n);
    Eigen::Matrix<double, Eigen::Dynamic, P> J(n, P);
    Lm out;
    double rss = residuals<P>(xs, q, r, &J);
    double lambda = 1e-3;
    int it = 0;
    for (; it < max_iterations && std::isfinite(rss); it++) {
        const MatP A = J.transpose() * J;
        const VecP g = J.transpose() * r;
        bool accepted = false;
        while (!accepted) {
            MatP H = A;
            for (int k = 0; k < P; k++)
                H(k, k) += lambda * std::max(A(k, k), 1e-12);
            const VecP step = H.ldlt().solve(-g);
            const Vec q_new = q + Vec(step);
            const double rss_new = step.allFinite() ? residuals<P>(xs, q_new, r_new, nullptr) : INFINITY;
            if (rss_new < rss) {
                const double gain = rss - rss_new;
                q = q_new;
                lambda = std::max(lambda / 3, 1e-12);
                accepted = true;
                const bool small = gain <= 1e-12 * rss + 1e-18 ||
                                   step.cwiseAbs().maxCoeff() <= 1e-10 * (1 + q.cwiseAbs().maxCoeff());
                rss = residuals<P>(xs, q, r, &J);
                if (small) {
                    out.converged = true;
                    break;
                }
            } else {
                lambda *= 4;
                if (lambda > 1e12) { // no step lowers the residual: a minimum, to the precision there is
                    out.converged = true;
                    break;
                }
            }
        }
        if (out.converged)
            break;
    }
    out.q = q;
    out.rss = rss;
    out.iterations = it + 1;
    out.converged = out.converged && std::isfinite(rss) && q.allFinite();
    return out;
}

// LM from q0, the priors in q0's form.
Lm fit_from(const Problem &pb, const Vec &q0, int max_iterations)
{
    Problem at{pb.xs, pb.data_sigma, {}};
    for (const Prior &p : pb.priors)
        at.priors.push_back(aligned(p, q0[ANGLE]));
    return q0.size() == kMeanderParams ? levenberg_marquardt<kMeanderParams>(at, q0, max_iterations)
                                       : levenberg_marquardt<kStraightParams>(at, q0, max_iterations);
}

double percentile(std::vector<double> v, double f)
{
    if (v.empty())
        return kNaN;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(f * (double)(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + (long)k, v.end());
    return v[k];
}

// A straight-front start for the direction `angle`, and its residual.
std::pair<Vec, double> start_at(const std::vector<Sample> &xs, double angle)
{
    const size_t n = xs.size();
    std::vector<std::pair<double, double>> rt(n); // (across, temperature)
    for (size_t i = 0; i < n; i++) {
        double s, r;
        front_frame(angle, xs[i].north_m, xs[i].east_m, s, r);
        rt[i] = {r, xs[i].temperature_c};
    }
    std::sort(rt.begin(), rt.end());
    const size_t quarter = std::max<size_t>(1, n / 4);
    double ta = 0, tb = 0;
    for (size_t i = 0; i < quarter; i++) {
        ta += rt[i].second;
        tb += rt[n - 1 - i].second;
    }
    ta /= (double)quarter;
    tb /= (double)quarter;
    const double mid = 0.5 * (ta + tb), half = 0.5 * std::fabs(tb - ta);
    std::vector<double> band, near;
    for (const auto &x : rt) {
        if (std::fabs(x.second - mid) < 0.8 * half)
            band.push_back(x.first);
        if (std::fabs(x.second - mid) < 0.5 * half)
            near.push_back(x.first);
    }
    std::vector<double> all(n);
    for (size_t i = 0; i < n; i++)
        all[i] = rt[i].first;
    const double offset = percentile(near.empty() ? all : near, 0.5);
    // |T - mid| < 0.8 half is |x| < 1.1 w: the band's 10-90 % spread is about 1.76 w
    double width = band.size() >= 4 ? (percentile(band, 0.9) - percentile(band, 0.1)) / 1.76 : 20.0;
    width = std::max(width, 1.0);
    Front f;
    f.offset_m = offset;
    f.angle_rad = angle;
    f.ta_c = ta;
    f.tb_c = tb;
    f.width_m = width;
    Vec q = to_q(f);
    return {q, rss_of(Problem{xs, 1.0, {}}, q)};
}

struct Cov {
    bool ok = false;
    int weakest = -1;       // the parameter the data determine least, when !ok
    Eigen::MatrixXd c;
};

// (J^T J)^-1 sigma^2, refused when J^T J is singular to the precision of doubles
// once scaled to a unit diagonal.
template <int P>
Cov covariance_p(const Problem &xs, const Vec &q, double sigma2)
{
    using MatP = Eigen::Matrix<double, P, P>;
    using VecP = Eigen::Matrix<double, P, 1>;
    const Eigen::Index n = xs.rows();
    Vec r(n);
    Eigen::Matrix<double, Eigen::Dynamic, P> J(n, P);
    residuals<P>(xs, q, r, &J);
    const MatP A = J.transpose() * J;
    Cov out;
    VecP d;
    for (int k = 0; k < P; k++) {
        if (!(A(k, k) > 0)) {
            out.weakest = k;
            return out;
        }
        d[k] = 1 / std::sqrt(A(k, k));
    }
    const MatP As = d.asDiagonal() * A * d.asDiagonal();
    // As = V S V^T (symmetric): singular values in decreasing order
    Eigen::JacobiSVD<MatP> svd(As, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const VecP sv = svd.singularValues();
    if (!(sv[P - 1] > 1e-10 * sv[0])) {
        Eigen::Index k;
        svd.matrixV().col(P - 1).cwiseAbs().maxCoeff(&k);
        out.weakest = (int)k;
        return out;
    }
    const MatP c = d.asDiagonal() * svd.matrixV() * sv.cwiseInverse().asDiagonal() * svd.matrixU().transpose() *
                   d.asDiagonal() * sigma2;
    out.c = c;
    out.ok = c.allFinite();
    return out;
}

Cov covariance(const Problem &xs, const Vec &q, double sigma2)
{
    return q.size() == kMeanderParams ? covariance_p<kMeanderParams>(xs, q, sigma2)
                                      : covariance_p<kStraightParams>(xs, q, sigma2);
}

// The front of q and its sigmas, canonical.
void report(const Vec &q, const Eigen::MatrixXd &c, Front &front, Front &sigma)
{
    const Front raw = from_q(q);
    front = canonical(raw);
    auto sd = [&](int k) { return std::sqrt(std::max(0.0, c(k, k))); };
    sigma = Front{};
    sigma.offset_m = sd(OFFSET);
    sigma.angle_rad = sd(ANGLE);
    const bool swapped = std::fabs(std::remainder(front.angle_rad - raw.angle_rad, 2 * kPi)) > 1.0;
    sigma.ta_c = sd(swapped ? TB : TA);
    sigma.tb_c = sd(swapped ? TA : TB);
    sigma.width_m = raw.width_m * sd(LOG_WIDTH);
    sigma.meander = raw.meander;
    if (raw.meander) {
        sigma.amplitude_m = sd(AMPLITUDE);
        sigma.wavelength_m = raw.wavelength_m * sd(LOG_WAVELENGTH);
        sigma.phase_rad = sd(PHASE);
    } else {
        front.wavelength_m = front.phase_rad = kNaN;
        sigma.wavelength_m = sigma.phase_rad = kNaN;
    }
}

FitResult refuse(Status st, int n, const char *fmt, double a = 0, double b = 0)
{
    FitResult f;
    f.status = st;
    f.n = n;
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, a, b);
    f.text = buf;
    return f;
}

}  // namespace

const char *status_name(Status s)
{
    switch (s) {
    case Status::OK: return "OK";
    case Status::TOO_FEW: return "TOO_FEW";
    case Status::DIVERGED: return "DIVERGED";
    }
    return "?";
}

FitResult fit_front(const std::vector<Sample> &xs, const FitOptions &opt, const Front *warm,
                    const std::vector<Prior> &priors, double data_sigma_c)
{
    const int n = static_cast<int>(xs.size());
    const bool fused = !priors.empty();
    for (const Sample &x : xs)
        if (!std::isfinite(x.temperature_c) || !std::isfinite(x.north_m) || !std::isfinite(x.east_m))
            return refuse(Status::DIVERGED, n, "a sample is not a number (at %.1f N %.1f E)", x.north_m, x.east_m);
    for (const Prior &p : priors)
        for (int k = 0; k < kStraightParams; k++)
            if (!(std::isfinite(to_q(p.front)[k]) && prior_sigma(p, k) > 0 && std::isfinite(prior_sigma(p, k))))
                return refuse(Status::DIVERGED, n, "a teammate's summary is not a number or has no sigma");
    if (fused && !(data_sigma_c > 0))
        return refuse(Status::DIVERGED, n, "no sigma for the samples beside the teammates' summaries");
    std::vector<double> temps(xs.size());
    for (size_t i = 0; i < xs.size(); i++)
        temps[i] = xs[i].temperature_c;
    const double contrast = n > 0 ? percentile(temps, 0.95) - percentile(temps, 0.05) : 0.0;
    const bool enough = n >= opt.min_samples, both_waters = contrast >= opt.min_contrast_c;
    if (!fused && !enough)
        return refuse(Status::TOO_FEW, n, "%.0f samples: the fit needs %.0f", n, opt.min_samples);
    if (!fused && !both_waters)
        return refuse(Status::TOO_FEW, n,
                      "the temperatures span %.2f degC (5th to 95th percentile), under %.2f: one water only",
                      contrast, opt.min_contrast_c);
    const Problem pb{xs, fused ? data_sigma_c : 1.0, priors};

    // 2. the straight front from the best starts (and the teammates' estimates)
    std::vector<std::pair<double, Vec>> starts;
    if (enough && both_waters) {
        for (int k = 0; k < 36; k++) {
            auto s = start_at(xs, k * kPi / 36);
            starts.push_back({s.second, s.first});
        }
        std::sort(starts.begin(), starts.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
        starts.resize(3);
    }
    if (warm && std::isfinite(warm->width_m) && warm->width_m > 0) {
        Front w = *warm;
        w.meander = false;
        starts.push_back({0, to_q(w)});
    }
    for (const Prior &p : priors) {
        Front f = p.front;
        f.meander = false;
        starts.push_back({0, to_q(f)});
    }
    Lm best;
    for (const auto &s : starts) {
        Lm lm = fit_from(pb, s.second, opt.max_iterations);
        if (lm.converged && lm.rss < best.rss)
            best = lm;
    }
    if (!best.converged)
        return refuse(Status::DIVERGED, n, "no start converged in %.0f iterations (no front of this shape in the data?)",
                      opt.max_iterations);
    const double rss5 = best.rss;

    // 3. the meander, where the samples near the front span enough of it
    std::string meander_note;
    {
        const Front f = from_q(best.q);
        std::vector<double> along;
        for (const Sample &x : xs) {
            double s, r;
            front_frame(f.angle_rad, x.north_m, x.east_m, s, r);
            if (std::fabs(r - f.offset_m) < 3 * f.width_m + 20)
                along.push_back(s);
        }
        const double span = along.size() > 10 ? percentile(along, 0.98) - percentile(along, 0.02) : 0.0;
        char buf[160];
        if (span < opt.meander_span_m) {
            std::snprintf(buf, sizeof buf, "; meander not fitted: the samples near the front span %.0f m along it, "
                                           "under %.0f", span, opt.meander_span_m);
            meander_note = buf;
        } else if (enough && both_waters && n > kMeanderParams + 10) {
            Lm mb;
            std::vector<Vec> mstarts;
            for (double lf : {0.5, 1.0, 2.0})
                for (int k = 0; k < 4; k++) {
                    Front m = f;
                    m.meander = true;
                    m.wavelength_m = std::max(lf * span, 4 * f.width_m);
                    m.amplitude_m = std::max(f.width_m, 0.05 * m.wavelength_m);
                    m.phase_rad = k * kPi / 2;
                    mstarts.push_back(to_q(m));
                }
            if (warm && warm->meander)
                mstarts.push_back(to_q(*warm));
            for (const Vec &q0 : mstarts) {
                Lm lm = fit_from(pb, q0, opt.max_iterations);
                if (lm.converged && lm.rss < mb.rss)
                    mb = lm;
            }
            bool keep = false;
            if (mb.converged && mb.rss < rss5) {
                const double F = (rss5 - mb.rss) / 3 / (mb.rss / (n - kMeanderParams));
                const Cov c = covariance(pb, mb.q, fused ? 1.0 : mb.rss / (n - kMeanderParams));
                const Front m = from_q(mb.q);
                const double sa = c.ok ? std::sqrt(c.c(AMPLITUDE, AMPLITUDE)) : INFINITY;
                keep = F > opt.meander_f && std::fabs(m.amplitude_m) > 3 * sa && m.wavelength_m <= 2 * span &&
                       m.width_m >= opt.min_width_m && m.width_m <= opt.max_width_m;
                if (!keep) {
                    std::snprintf(buf, sizeof buf, "; meander not significant (F %.1f, amplitude %.1f +- %.1f m, "
                                                   "wavelength %.0f m)", F, m.amplitude_m, sa, m.wavelength_m);
                    meander_note = buf;
                }
            } else {
                meander_note = "; meander tried, did not converge";
            }
            if (keep)
                best = mb;
        }
    }

    // 4. the checks, the covariance, the report
    const int p = static_cast<int>(best.q.size());
    const Front raw = from_q(best.q);
    if (!(raw.width_m >= opt.min_width_m && raw.width_m <= opt.max_width_m))
        return refuse(Status::DIVERGED, n,
                      raw.width_m > opt.max_width_m
                          ? "width %.3g m: no front in the data (a gradient, wider than %.0f m)"
                          : "width %.3g m: a step no sample lies in (under %.1f m)",
                      raw.width_m, raw.width_m > opt.max_width_m ? opt.max_width_m : opt.min_width_m);
    // with priors the residuals are in sigmas already (the samples' sigma given)
    const double sigma2 = fused ? 1.0 : best.rss / std::max(1, n - p);
    Problem at{xs, pb.data_sigma, {}};
    for (const Prior &pr : priors)
        at.priors.push_back(aligned(pr, best.q[ANGLE]));
    const Cov cov = covariance(at, best.q, sigma2);
    if (!cov.ok) {
        FitResult f = refuse(Status::DIVERGED, n, "the data do not determine the front (J^T J singular)");
        if (cov.weakest >= 0)
            f.text = std::string("the data do not determine the ") + kParamNames[cov.weakest] +
                     " (J^T J singular: one straight pass across the front?)";
        return f;
    }
    FitResult out;
    out.status = Status::OK;
    out.n = n;
    out.iterations = best.iterations;
    double rss_c = 0;  // of the samples alone, in degC
    for (const Sample &x : xs) {
        const double d = model(best.q, x.north_m, x.east_m) - x.temperature_c;
        rss_c += d * d;
    }
    out.rms_c = n > 0 ? std::sqrt(rss_c / n) : 0.0;
    report(best.q, cov.c, out.front, out.sigma);
    char buf[200];
    const char *shape = out.front.meander ? "meandering" : "straight";
    const std::string team = std::to_string(priors.size()) + (priors.size() == 1 ? " teammate's summary" : " teammates' summaries");
    if (n == 0) {
        out.text = std::string(shape) + " front from " + team + " only (no samples of its own)";
        return out;
    }
    std::snprintf(buf, sizeof buf, "%s front from %d samples, rms %.3f degC", shape, n, out.rms_c);
    out.text = buf;
    if (fused)
        out.text += " and " + team;
    out.text += meander_note;
    return out;
}

}  // namespace frontest

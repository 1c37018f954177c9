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

// Residuals (model - data) and, with J, the Jacobian; the sum of squares.
// Fixed sizes for the P parameters (5 or 8): Eigen's dynamic-size solvers
// trip GCC's maybe-uninitialized under -Werror.
template <int P>
double residuals(const std::vector<Sample> &xs, const Vec &q, Vec &r, Eigen::Matrix<double, Eigen::Dynamic, P> *J)
{
    double grad[kMeanderParams];
    double rss = 0;
    for (size_t i = 0; i < xs.size(); i++) {
        const double m = model(q, xs[i].north_m, xs[i].east_m, J ? grad : nullptr);
        r[(Eigen::Index)i] = m - xs[i].temperature_c;
        rss += r[(Eigen::Index)i] * r[(Eigen::Index)i];
        if (J)
            for (int k = 0; k < P; k++)
                (*J)((Eigen::Index)i, k) = grad[k];
    }
    return rss;
}

double rss_of(const std::vector<Sample> &xs, const Vec &q)
{
    Vec r((Eigen::Index)xs.size());
    return residuals<kStraightParams>(xs, q, r, nullptr);
}

// Levenberg-Marquardt (Marquardt's scaling: lambda times the diagonal of J^T J).
template <int P>
Lm levenberg_marquardt(const std::vector<Sample> &xs, Vec q, int max_iterations)
{
    using MatP = Eigen::Matrix<double, P, P>;
    using VecP = Eigen::Matrix<double, P, 1>;
    const Eigen::Index n = (Eigen::Index)xs.size();
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

Lm fit_from(const std::vector<Sample> &xs, const Vec &q0, int max_iterations)
{
    return q0.size() == kMeanderParams ? levenberg_marquardt<kMeanderParams>(xs, q0, max_iterations)
                                       : levenberg_marquardt<kStraightParams>(xs, q0, max_iterations);
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
    return {q, rss_of(xs, q)};
}

struct Cov {
    bool ok = false;
    int weakest = -1;       // the parameter the data determine least, when !ok
    Eigen::MatrixXd c;
};

// (J^T J)^-1 sigma^2, refused when J^T J is singular to the precision of doubles
// once scaled to a unit diagonal.
template <int P>
Cov covariance_p(const std::vector<Sample> &xs, const Vec &q, double sigma2)
{
    using MatP = Eigen::Matrix<double, P, P>;
    using VecP = Eigen::Matrix<double, P, 1>;
    const Eigen::Index n = (Eigen::Index)xs.size();
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

Cov covariance(const std::vector<Sample> &xs, const Vec &q, double sigma2)
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

FitResult fit_front(const std::vector<Sample> &xs, const FitOptions &opt, const Front *warm)
{
    const int n = static_cast<int>(xs.size());
    if (n < opt.min_samples)
        return refuse(Status::TOO_FEW, n, "%.0f samples: the fit needs %.0f", n, opt.min_samples);
    for (const Sample &x : xs)
        if (!std::isfinite(x.temperature_c) || !std::isfinite(x.north_m) || !std::isfinite(x.east_m))
            return refuse(Status::DIVERGED, n, "a sample is not a number (at %.1f N %.1f E)", x.north_m, x.east_m);
    std::vector<double> temps(xs.size());
    for (size_t i = 0; i < xs.size(); i++)
        temps[i] = xs[i].temperature_c;
    const double contrast = percentile(temps, 0.95) - percentile(temps, 0.05);
    if (!(contrast >= opt.min_contrast_c))
        return refuse(Status::TOO_FEW, n,
                      "the temperatures span %.2f degC (5th to 95th percentile), under %.2f: one water only",
                      contrast, opt.min_contrast_c);

    // 2. the straight front from the best starts
    std::vector<std::pair<double, Vec>> starts;
    for (int k = 0; k < 36; k++) {
        auto s = start_at(xs, k * kPi / 36);
        starts.push_back({s.second, s.first});
    }
    std::sort(starts.begin(), starts.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
    starts.resize(3);
    if (warm && std::isfinite(warm->width_m) && warm->width_m > 0) {
        Front w = *warm;
        w.meander = false;
        starts.push_back({0, to_q(w)});
    }
    Lm best;
    for (const auto &s : starts) {
        Lm lm = fit_from(xs, s.second, opt.max_iterations);
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
        } else if (n > kMeanderParams + 10) {
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
                Lm lm = fit_from(xs, q0, opt.max_iterations);
                if (lm.converged && lm.rss < mb.rss)
                    mb = lm;
            }
            bool keep = false;
            if (mb.converged && mb.rss < rss5) {
                const double F = (rss5 - mb.rss) / 3 / (mb.rss / (n - kMeanderParams));
                const Cov c = covariance(xs, mb.q, mb.rss / (n - kMeanderParams));
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
    const double sigma2 = best.rss / std::max(1, n - p);
    const Cov cov = covariance(xs, best.q, sigma2);
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
    out.rms_c = std::sqrt(best.rss / n);
    report(best.q, cov.c, out.front, out.sigma);
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s front from %d samples, rms %.3f degC", out.front.meander ? "meandering" : "straight",
                  n, out.rms_c);
    out.text = std::string(buf) + meander_note;
    return out;
}

}  // namespace frontest

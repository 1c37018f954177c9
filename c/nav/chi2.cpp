#include "nav/chi2.hpp"

#include <cmath>
#include <limits>

namespace nav {

double chi2_cdf(int dof, double x)
{
    if (x <= 0)
        return 0;
    // Closed forms exist for the low degrees of freedom a gate needs.
    const double half = std::sqrt(0.5 * x);
    switch (dof) {
    case 1: return std::erf(half);
    case 2: return 1.0 - std::exp(-0.5 * x);
    case 3: return std::erf(half) - std::sqrt(2.0 * x / M_PI) * std::exp(-0.5 * x);
    default: return std::numeric_limits<double>::quiet_NaN();
    }
}

double chi2_quantile(int dof, double p)
{
    if (!(p > 0 && p < 1) || dof < 1 || dof > 3)
        return std::numeric_limits<double>::quiet_NaN();
    // The CDF is monotonic: bisection is exact enough and runs once at load.
    double lo = 0, hi = 1;
    while (chi2_cdf(dof, hi) < p)
        hi *= 2;
    for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; i++) {
        double mid = 0.5 * (lo + hi);
        (chi2_cdf(dof, mid) < p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace nav

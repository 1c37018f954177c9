// Chi-square quantiles for the innovation gate (1 to 3 degrees of freedom).
#ifndef NAV_CHI2_HPP
#define NAV_CHI2_HPP

namespace nav {

// P(X <= x) for X ~ chi-square(dof), dof in 1..3.
double chi2_cdf(int dof, double x);
// The x with chi2_cdf(dof, x) = p, for p in (0, 1); NaN outside.
double chi2_quantile(int dof, double p);

}  // namespace nav

#endif

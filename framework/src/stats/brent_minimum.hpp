#pragma once
// One-dimensional minimisation without derivatives: Brent's method (golden section with
// parabolic interpolation; R. P. Brent, "Algorithms for Minimization without Derivatives", 1973,
// ch. 5), step for step as R's `optimize()` runs it, so estimators defined through `optimize` in
// R packages (the robust wavelet variance of `wv`) give the same numbers here.

#include <functional>

namespace stochnav {

/// R's default `optimize` tolerance, .Machine$double.eps^0.25 (about 1.2e-4).
double r_optimize_tolerance();

/// A local minimiser of f on [lower, upper] (lower < upper), found to within
/// sqrt(DBL_EPSILON) |x| + tolerance / 3. Never evaluates f at the end points. f is called about
/// 15 - 40 times.
double brent_minimum(const std::function<double(double)>& f, double lower, double upper,
                     double tolerance);

}  // namespace stochnav

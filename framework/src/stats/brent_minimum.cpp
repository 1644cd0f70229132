#include "brent_minimum.hpp"

#include <cfloat>
#include <cmath>

namespace stochnav {

double r_optimize_tolerance() { return std::pow(DBL_EPSILON, 0.25); }

double brent_minimum(const std::function<double(double)>& f, double lower, double upper,
                     double tolerance) {
  const double golden = (3.0 - std::sqrt(5.0)) * 0.5;  // squared inverse of the golden ratio
  const double sqrt_epsilon = std::sqrt(DBL_EPSILON);
  double a = lower;
  double b = upper;
  // x: best point so far; w: second best; v: the previous w. d: the last step; e: the one
  // before it (a parabolic step must be shorter than half of that).
  double x = a + golden * (b - a);
  double w = x;
  double v = x;
  double fx = f(x);
  double fw = fx;
  double fv = fx;
  double d = 0.0;
  double e = 0.0;
  const double tolerance_third = tolerance / 3.0;
  for (;;) {
    const double middle = (a + b) * 0.5;
    const double tol1 = sqrt_epsilon * std::fabs(x) + tolerance_third;
    const double tol2 = tol1 * 2.0;
    if (std::fabs(x - middle) <= tol2 - (b - a) * 0.5) break;

    double p = 0.0;
    double q = 0.0;
    double r = 0.0;
    if (std::fabs(e) > tol1) {  // a parabola through x, w and v
      r = (x - w) * (fx - fv);
      q = (x - v) * (fx - fw);
      p = (x - v) * q - (x - w) * r;
      q = (q - r) * 2.0;
      if (q > 0.0) {
        p = -p;
      } else {
        q = -q;
      }
      r = e;
      e = d;
    }
    double u = 0.0;
    if (std::fabs(p) >= std::fabs(q * 0.5 * r) || p <= q * (a - x) || p >= q * (b - x)) {
      e = x < middle ? b - x : a - x;  // golden section into the larger part
      d = golden * e;
    } else {  // the parabola's minimum, kept away from the ends
      d = p / q;
      u = x + d;
      if (u - a < tol2 || b - u < tol2) d = x >= middle ? -tol1 : tol1;
    }
    // Never closer to x than tol1.
    if (std::fabs(d) >= tol1) {
      u = x + d;
    } else if (d > 0.0) {
      u = x + tol1;
    } else {
      u = x - tol1;
    }
    const double fu = f(u);
    if (fu <= fx) {
      if (u < x) {
        b = x;
      } else {
        a = x;
      }
      v = w;
      fv = fw;
      w = x;
      fw = fx;
      x = u;
      fx = fu;
    } else {
      if (u < x) {
        a = u;
      } else {
        b = u;
      }
      if (fu <= fw || w == x) {
        v = w;
        fv = fw;
        w = u;
        fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u;
        fv = fu;
      }
    }
  }
  return x;
}

}  // namespace stochnav

#include "stochnav/stats/confidence.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <limits>

namespace stochnav {

DeviationInterval chi_square_interval(double deviation, double edf, double confidence) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(edf > 0.0) || !std::isfinite(edf) || !(confidence > 0.0) || !(confidence < 1.0)) {
    return {nan, nan};
  }
  const boost::math::chi_squared_distribution<double> chi_square(edf);
  const double tail = 0.5 * (1.0 - confidence);
  const double chi2_low = boost::math::quantile(chi_square, tail);
  const double chi2_high = boost::math::quantile(chi_square, 1.0 - tail);
  return {deviation * std::sqrt(edf / chi2_high), deviation * std::sqrt(edf / chi2_low)};
}

}  // namespace stochnav

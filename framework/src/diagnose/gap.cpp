#include "stochnav/diagnose/gap.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/trigamma.hpp>
#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/fit/oadev_covariance.hpp"
#include "stochnav/model/allan_variance.hpp"

namespace stochnav {

AvarGap avar_gap(const NoiseModel& model, const AvarMeasurement& measured) {
  const double duration_s = static_cast<double>(measured.phase_count - 1) * measured.tau0_s;
  const StationaryEquivalent equivalent = stationary_equivalent(model, duration_s);
  const Eigen::MatrixXd covariance = oadev_estimate_covariance(equivalent.model, measured.tau0_s,
                                                               measured.phase_count, measured.m) *
                                     equivalent.variance_inflation;
  const auto count = static_cast<Eigen::Index>(measured.m.size());
  AvarGap gap;
  Eigen::VectorXd inv_sd(count);
  double sum_z2 = 0.0;
  for (Eigen::Index i = 0; i < count; ++i) {
    const auto index = static_cast<std::size_t>(i);
    AvarGapPoint point;
    point.tau_s = measured.tau_s[index];
    point.avar_measured = measured.avar[index];
    point.avar_model = allan_variance(equivalent.model, point.tau_s);
    if (!(point.avar_model > 0.0) || !std::isfinite(point.avar_model)) {
      throw ConfigError(fmt::format(
          "the noise model's Allan variance is {} at tau = {} s; give the model a term with a "
          "positive Allan variance at every measured tau (e.g. angle_random_walk N > 0)",
          point.avar_model, point.tau_s));
    }
    const double terms = static_cast<double>(measured.phase_count - 2 * measured.m[index]);
    const double variance = covariance(i, i);
    double edf =
        variance > 0.0 ? 2.0 * point.avar_model * point.avar_model / variance : 2.0 * terms;
    edf = std::clamp(edf, 1e-3, 2.0 * terms);
    point.edf_model = edf;
    const double half = 0.5 * edf;
    const double bias = boost::math::digamma(half) - std::log(half);
    const double sd = std::sqrt(boost::math::trigamma(half));
    point.z = (std::log(point.avar_measured) - std::log(point.avar_model) - bias) / sd;
    sum_z2 += point.z * point.z;
    inv_sd[i] = variance > 0.0 ? 1.0 / std::sqrt(variance) : 0.0;
    gap.points.push_back(point);
  }
  // Correlation of the estimates; points without stochastic scatter count as independent.
  Eigen::MatrixXd correlation = inv_sd.asDiagonal() * covariance * inv_sd.asDiagonal();
  for (Eigen::Index i = 0; i < count; ++i) {
    if (inv_sd[i] == 0.0) {
      correlation.row(i).setZero();
      correlation.col(i).setZero();
    }
    correlation(i, i) = 1.0;
  }
  const double m = static_cast<double>(count);
  gap.reduced_chi_square = count > 0 ? sum_z2 / m : 0.0;
  const double trace_r2 = (correlation.array() * correlation.array()).sum();
  gap.effective_dof = count > 0 ? m * m / trace_r2 : 0.0;
  return gap;
}

AvarGap screening_avar_gap(const NoiseModel& model, const AvarMeasurement& measured,
                           const AvarGap& reference) {
  const double duration_s = static_cast<double>(measured.phase_count - 1) * measured.tau0_s;
  const NoiseModel equivalent = stationary_equivalent(model, duration_s).model;
  AvarGap gap;
  gap.effective_dof = reference.effective_dof;
  double sum_z2 = 0.0;
  for (std::size_t i = 0; i < reference.points.size(); ++i) {
    AvarGapPoint point = reference.points[i];
    point.avar_model = allan_variance(equivalent, point.tau_s);
    if (!(point.avar_model > 0.0) || !std::isfinite(point.avar_model)) {
      throw ConfigError(
          fmt::format("a candidate noise model's Allan variance is {} at tau = {} s; give "
                      "the model a term with a positive Allan variance there",
                      point.avar_model, point.tau_s));
    }
    const double half = 0.5 * point.edf_model;
    const double bias = boost::math::digamma(half) - std::log(half);
    const double sd = std::sqrt(boost::math::trigamma(half));
    point.z = (std::log(point.avar_measured) - std::log(point.avar_model) - bias) / sd;
    sum_z2 += point.z * point.z;
    gap.points.push_back(point);
  }
  gap.reduced_chi_square =
      gap.points.empty() ? 0.0 : sum_z2 / static_cast<double>(gap.points.size());
  return gap;
}

namespace {

double reduced_quantile(double dof, double probability) {
  if (!(dof > 0.0)) return 1.0;
  const boost::math::chi_squared_distribution<double> distribution(dof);
  return boost::math::quantile(distribution, probability) / dof;
}

}  // namespace

Gap combine_gap(AvarGap avar, StationarityTest stationarity, double alpha) {
  Gap gap;
  gap.dof = avar.effective_dof + stationarity.dof;
  gap.chi_square = avar.effective_dof * avar.reduced_chi_square +
                   stationarity.dof * stationarity.reduced_chi_square;
  gap.value = stationarity.dof > 0.0
                  ? std::max(avar.reduced_chi_square, stationarity.reduced_chi_square)
                  : avar.reduced_chi_square;
  gap.avar_threshold = reduced_quantile(avar.effective_dof, 1.0 - 0.5 * alpha);
  gap.stationarity_threshold = reduced_quantile(stationarity.dof, 1.0 - 0.5 * alpha);
  gap.consistent =
      avar.reduced_chi_square <= gap.avar_threshold &&
      (stationarity.dof <= 0.0 || stationarity.reduced_chi_square <= gap.stationarity_threshold);
  gap.avar = std::move(avar);
  gap.stationarity = std::move(stationarity);
  return gap;
}

}  // namespace stochnav

#include "stochnav/fit/fit_data.hpp"

#include <fmt/format.h>

#include <cmath>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

std::string check_positive(const std::vector<double>& values, std::string_view name) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]) || !(values[i] > 0.0)) {
      return fmt::format("{}[{}] = {} is not a finite number > 0", name, i, values[i]);
    }
  }
  return {};
}

}  // namespace

std::string validate(const FitData& data) {
  if (data.tau_s.empty()) {
    return "no Allan deviation points to fit (the record is too short for any averaging time, or "
           "every point is zero); give a longer record";
  }
  if (data.avar.size() != data.tau_s.size() || data.edf.size() != data.tau_s.size()) {
    return fmt::format("tau_s, avar and edf have different lengths ({}, {}, {})",
                       data.tau_s.size(), data.avar.size(), data.edf.size());
  }
  for (const auto& [values, name] : {std::pair{&data.tau_s, "tau_s"}, std::pair{&data.avar, "avar"},
                                     std::pair{&data.edf, "edf"}}) {
    if (auto problem = check_positive(*values, name); !problem.empty()) return problem;
  }
  if (!std::isfinite(data.rate_hz) || !(data.rate_hz > 0.0)) {
    return fmt::format("rate_hz = {} is not a sampling rate > 0", data.rate_hz);
  }
  return {};
}

FitData fit_data_from_deviations(Deviation kind, std::span<const DeviationPoint> points,
                                 Unit unit, double rate_hz) {
  if (kind != Deviation::kOadev && kind != Deviation::kAdev) {
    throw ConfigError(fmt::format(
        "fit: {} values are not Allan variances; expected an adev or oadev table",
        deviation_name(kind)));
  }
  FitData data;
  data.unit = unit;
  data.rate_hz = rate_hz;
  const double scale = si_per_unit(unit);
  for (const auto& point : points) {
    if (!(point.deviation > 0.0) || !std::isfinite(point.deviation)) continue;
    if (!(point.edf > 0.0) || !std::isfinite(point.edf)) continue;
    const double deviation = scale * point.deviation;
    data.tau_s.push_back(point.tau_s);
    data.avar.push_back(deviation * deviation);
    data.edf.push_back(point.edf);
    if (kind == Deviation::kOadev && data.phase_count == 0) {
      data.phase_count = point.terms + 2 * point.m;
    }
  }
  return data;
}

FitData fit_data_from_adev(std::span<const double> tau_s, std::span<const double> adev_natural,
                           std::span<const double> edf, Unit unit, double rate_hz,
                           std::size_t phase_count) {
  FitData data;
  data.unit = unit;
  data.rate_hz = rate_hz;
  data.phase_count = phase_count;
  data.tau_s.assign(tau_s.begin(), tau_s.end());
  data.edf.assign(edf.begin(), edf.end());
  for (double adev : adev_natural) data.avar.push_back(adev * adev);
  return data;
}

}  // namespace stochnav

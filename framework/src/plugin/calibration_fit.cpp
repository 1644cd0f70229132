#include "stochnav/plugin/calibration_fit.hpp"

#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_data.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav::plugin {

std::array<FitResult, 3> fit_calibration_axes(const CalibrationRecord& record,
                                              const FitOptions& options) {
  if (!(record.rate_hz > 0.0)) {
    throw InputError(record.source + ": calibration rate must be > 0 Hz; give the record's rate");
  }
  const Unit unit =
      record.group == SensorGroup::kGyro ? Unit::kRadPerSecond : Unit::kMeterPerSecondSquared;
  const double tau0 = 1.0 / record.rate_hz;
  std::array<FitResult, 3> results;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const auto& values = record.axes[axis];
    if (values.size() != record.axes[0].size()) {
      throw InputError(record.source +
                       ": calibration axes differ in length; give three equal "
                       "columns");
    }
    const std::vector<double> phase = phase_from_rate(values, tau0);
    const auto m_values =
        averaging_factors(Deviation::kOadev, TauSpacing::kOctave, phase.size(), tau0);
    if (m_values.size() < 2) {
      throw InputError(record.source + ": calibration record too short for a fit (" +
                       std::to_string(values.size()) + " samples); use a longer static record");
    }
    const auto points = compute_deviation(Deviation::kOadev, phase, tau0, m_values);
    results[axis] = fit_noise_terms(
        fit_data_from_deviations(Deviation::kOadev, points, unit, record.rate_hz), options);
  }
  return results;
}

nlohmann::json calibration_fit_quality(const std::array<FitResult, 3>& fits) {
  const auto number_or_null = [](double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
  };
  nlohmann::json quality = nlohmann::json::object();
  const char* names[] = {"x", "y", "z"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const FitDiagnostics& d = fits[axis].diagnostics;
    quality[names[axis]] = {
        {"chi_square", number_or_null(d.chi_square)},
        {"dof", d.points > d.parameters ? d.points - d.parameters : 0},
        {"chi_square_per_dof", number_or_null(d.reduced_chi_square())},
        {"p_value", number_or_null(d.chi_square_p_value())},
        {"at_bound", d.at_bound}};
  }
  return quality;
}

const NoiseTerm* find_term(const NoiseModel& model, TermType type) {
  for (const auto& term : model.terms) {
    if (term_type(term) == type) return &term;
  }
  return nullptr;
}

}  // namespace stochnav::plugin

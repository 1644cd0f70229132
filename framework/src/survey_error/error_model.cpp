#include "stochnav/survey_error/error_model.hpp"

#include <array>

#include "mwd_models.hpp"
#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/survey_error/tool_models.hpp"

namespace stochnav::survey_error {

std::string_view propagation_mode_letter(PropagationMode mode) {
  switch (mode) {
    case PropagationMode::kRandom:
      return "R";
    case PropagationMode::kSystematic:
      return "S";
    case PropagationMode::kPerWell:
      return "W";
    case PropagationMode::kGlobal:
      return "G";
  }
  return "?";
}

std::string_view magnitude_unit_name(MagnitudeUnit unit) {
  switch (unit) {
    case MagnitudeUnit::kMetre:
      return "m";
    case MagnitudeUnit::kPerMetre:
      return "1/m";
    case MagnitudeUnit::kMetrePerSecond2:
      return "m/s2";
    case MagnitudeUnit::kNanotesla:
      return "nT";
    case MagnitudeUnit::kDimensionless:
      return "-";
    case MagnitudeUnit::kDegree:
      return "deg";
    case MagnitudeUnit::kDegreeNanotesla:
      return "deg.nT";
    case MagnitudeUnit::kDegreePerHour:
      return "deg/h";
  }
  return "?";
}

double ErrorSource::magnitude_si() const {
  if (unit == MagnitudeUnit::kDegreePerHour) return magnitude * kRadPerDeg / 3600.0;
  const bool in_degrees = unit == MagnitudeUnit::kDegree || unit == MagnitudeUnit::kDegreeNanotesla;
  return in_degrees ? magnitude * kRadPerDeg : magnitude;
}

std::span<const std::string> survey_error_model_names() {
  static const std::array<std::string, 2> names = {"mwd_rev5", "mwd_rev4"};
  return names;
}

const SurveyErrorModel& survey_error_model(std::string_view name) {
  static const SurveyErrorModel rev5 = make_mwd_rev5_model();
  static const SurveyErrorModel rev4 = make_mwd_rev4_model();
  if (name == rev5.name) return rev5;
  if (name == rev4.name) return rev4;
  check_tool_model_name(name, "--model");
  throw ConfigError("--model '" + std::string(name) +
                    "': not an ISCWSA MWD model; use mwd_rev5 or mwd_rev4");
}

}  // namespace stochnav::survey_error

#include "stochnav/survey_error/tool_models.hpp"

#include <algorithm>
#include <array>
#include <iterator>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/nearest_name.hpp"
#include "stochnav/survey_error/error_model.hpp"

namespace stochnav::survey_error {

std::span<const std::string> tool_model_names() {
  static const std::array<std::string, 5> names = {
      "mwd_rev5", "mwd_rev4", std::string(kGyroNsCtModelName), std::string(kGyroNsModelName),
      std::string(kGyroMwdModelName)};
  return names;
}

bool is_gyro_tool_model(std::string_view name) {
  return name == kGyroNsCtModelName || name == kGyroNsModelName || name == kGyroMwdModelName;
}

void check_tool_model_name(std::string_view name, std::string_view where) {
  const auto names = tool_model_names();
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  std::string message =
      std::string(where) + " '" + std::string(name) + "': unknown survey error model; ";
  if (const auto nearest = nearest_name(name, names)) {
    message += "did you mean '" + *nearest + "'?";
  } else {
    message +=
        "use mwd_rev5 (ISCWSA MWD Rev5.11), mwd_rev4 (ISCWSA MWD Rev4), gyro_ns_ct, gyro_ns or "
        "gyro_mwd (the OWSG gyro tool models GYRO-NS-CT, GYRO-NS, GYRO-MWD)";
  }
  throw ConfigError(message);
}

std::string tool_model_title(std::string_view name) {
  if (name == kGyroNsCtModelName) return "OWSG GYRO-NS-CT (rev 5)";
  if (name == kGyroNsModelName) return gyro_ns_model().title;
  if (name == kGyroMwdModelName) return gyro_mwd_model().title;
  return survey_error_model(name).title;
}

SurveyCovariance tool_model_covariance(std::string_view name,
                                       std::span<const ListingStation> stations,
                                       const WellParameters& well,
                                       const ContinuousGyroTerms& gyro) {
  check_tool_model_name(name, "--model");
  if (name == kGyroNsModelName) return propagate_survey_errors(gyro_ns_model(), stations, well);
  if (name == kGyroMwdModelName) return propagate_survey_errors(gyro_mwd_model(), stations, well);
  if (name != kGyroNsCtModelName) {
    return propagate_survey_errors(survey_error_model(name), stations, well);
  }
  SurveyCovariance result = propagate_survey_errors(gyro_ns_ct_table_model(gyro), stations, well);
  std::vector<SourceCovariance> continuous = continuous_gyro_covariance(gyro, stations, well);
  for (const SourceCovariance& source : continuous) {
    for (std::size_t k = 0; k < stations.size(); ++k) result.total_nev_m2[k] += source.nev_m2[k];
  }
  // The OWSG order: the continuous-gyro terms after the gyrocompass terms, before SAGE.
  const auto after_g4 = std::find_if(result.sources.begin(), result.sources.end(),
                                     [](const SourceCovariance& s) { return s.code == "GXY-G4"; });
  result.sources.insert(after_g4 == result.sources.end() ? after_g4 : after_g4 + 1,
                        std::make_move_iterator(continuous.begin()),
                        std::make_move_iterator(continuous.end()));
  return result;
}

}  // namespace stochnav::survey_error

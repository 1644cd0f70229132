#include "run/survey_start.hpp"

#include <fmt/format.h>

#include <cmath>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/ins/mwd_attitude.hpp"

namespace stochnav {
namespace {

constexpr const char* kTieOnMdPointer = "/initial_state/tie_on/measured_depth_m";
/// The pipe_length aid's defaults (plugins/aiding/pipe_length, docs/config-reference.md).
constexpr double kPipeLengthRandomSigmaM = 0.05;
constexpr double kPipeLengthScaleSigma = 1e-3;

}  // namespace

double sensor_md_m(const plugin::RunConfig& config, double tally_md_m) {
  return tally_md_m - config.survey.sensor_to_bit_m;
}

std::optional<double> tally_md_at_start_m(const plugin::AidData& aid_data) {
  if (!aid_data.has("measured_depth_m")) return std::nullopt;
  const std::span<const double> tally = aid_data.column("measured_depth_m", "/data/aids");
  if (tally.empty()) return std::nullopt;
  if (!aid_data.has("zupt")) return tally.front();
  const std::span<const double> at_rest = aid_data.column("zupt", "/data/aids");
  StationaryDepthMean mean;
  for (std::size_t row = 0; row < tally.size() && at_rest[row] != 0.0; ++row) mean.add(tally[row]);
  return mean.count() > 0 ? mean.mean_m() : tally.front();
}

void check_tie_on_against_tally(const plugin::RunConfig& config,
                                std::optional<double> tally_at_start_m) {
  if (!config.initial_state || !config.initial_state->tie_on.measured_depth_m ||
      !tally_at_start_m) {
    return;
  }
  const double configured_m = *config.initial_state->tie_on.measured_depth_m;
  const double from_tally_m = sensor_md_m(config, *tally_at_start_m);
  if (std::abs(configured_m - from_tally_m) <= config.survey.tie_on_md_tolerance_m) return;
  throw ConfigError(fmt::format(
      "{}: {} m, but the depth data's tally at the start (measured_depth_m, {:.3f} m) minus "
      "/survey/sensor_to_bit_m {} m gives {:.3f} m, more than /survey/tie_on_md_tolerance_m {} "
      "m away; correct the tie-on MD or the sensor-to-bit offset (or leave measured_depth_m "
      "out to take it from the tally)",
      kTieOnMdPointer, configured_m, *tally_at_start_m, config.survey.sensor_to_bit_m, from_tally_m,
      config.survey.tie_on_md_tolerance_m));
}

SurveyTieOn survey_tie_on(const plugin::RunConfig& config, const NavState& start,
                          const NavState& attitude, std::optional<double> tally_at_start_m) {
  SurveyTieOn tie_on{start.latitude_rad, start.longitude_rad, start.height_m,
                     tally_at_start_m ? sensor_md_m(config, *tally_at_start_m) : 0.0};
  if (config.initial_state && config.initial_state->tie_on.measured_depth_m) {
    tie_on.measured_depth_m = *config.initial_state->tie_on.measured_depth_m;
  }
  if (config.initial_state && config.initial_state->attitude) {
    tie_on.direction = SurveyDirection{config.initial_state->attitude->inclination_deg,
                                       config.initial_state->attitude->azimuth_deg};
  } else {
    const MwdAttitude angles = mwd_from_quaternion(attitude.q_nb);
    tie_on.direction =
        SurveyDirection{angles.inclination_rad * kDegPerRad, angles.azimuth_rad * kDegPerRad};
  }
  return tie_on;
}

std::optional<DepthReadingSigma> stated_depth_sigma(const plugin::RunConfig& config) {
  for (const plugin::PluginConfig& aid : config.aids) {
    if (aid.type != "pipe_length") continue;
    return DepthReadingSigma{aid.params.value("sigma_random_m", kPipeLengthRandomSigmaM),
                             aid.params.value("sigma_scale", kPipeLengthScaleSigma)};
  }
  return std::nullopt;
}

}  // namespace stochnav

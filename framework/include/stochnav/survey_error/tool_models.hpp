#pragma once
// The survey tool models `stochnav survey --model` and a run's "survey/error_model" name: the
// ISCWSA MWD models of error_model.hpp and the OWSG continuous-gyro terms of GYRO-NS-CT
// (continuous_gyro.hpp), each giving a SurveyCovariance (error_propagation.hpp).

#include <span>
#include <string>
#include <string_view>

#include "stochnav/survey_error/continuous_gyro.hpp"
#include "stochnav/survey_error/error_propagation.hpp"

namespace stochnav::survey_error {

/// The GYRO-NS-CT continuous-gyro terms GXY-RN, GXY-GD, GXY-GRW (and nothing else of that tool
/// model).
inline constexpr std::string_view kGyroNsCtModelName = "gyro_ns_ct";

/// "mwd_rev5", "mwd_rev4", "gyro_ns_ct".
std::span<const std::string> tool_model_names();

/// Throws ConfigError "<where> 'NAME': unknown survey error model; did you mean 'X'?" (or the
/// list of models) unless `name` is one of tool_model_names(). `where` names the option or
/// JSON pointer ("--model", "/survey/error_model").
void check_tool_model_name(std::string_view name, std::string_view where);

/// A title for messages: the MWD model's, or "OWSG GYRO-NS-CT continuous-gyro terms".
std::string tool_model_title(std::string_view name);

/// The covariance of `stations` under the model `name` (checked as check_tool_model_name with
/// "--model"). `gyro` gives the continuous-gyro terms (used by gyro_ns_ct only). Throws as
/// propagate_survey_errors and continuous_gyro_covariance.
SurveyCovariance tool_model_covariance(std::string_view name,
                                       std::span<const ListingStation> stations,
                                       const WellParameters& well, const ContinuousGyroTerms& gyro);

}  // namespace stochnav::survey_error

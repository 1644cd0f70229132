#pragma once
// The survey tool models `stochnav survey --model` and a run's "survey/error_model" name: the
// ISCWSA MWD models of error_model.hpp, the OWSG gyro tool model GYRO-NS-CT (its table of
// ISCWSA-propagated sources, gyro_ns_ct_table_model, and its continuous-gyro terms,
// continuous_gyro.hpp) and the OWSG stationary gyro tool models GYRO-NS and GYRO-MWD (tables
// only), each giving a SurveyCovariance (error_propagation.hpp).

#include <span>
#include <string>
#include <string_view>

#include "stochnav/survey_error/continuous_gyro.hpp"
#include "stochnav/survey_error/error_propagation.hpp"

namespace stochnav::survey_error {

/// The OWSG gyro tool model GYRO-NS-CT (rev 5), all 19 sources in the OWSG order:
///   DRFR, DSFS, DSTG, XYM1, XYM2, XYM3E, XYM4E, XCLA, XCLH, AXYZ-MIS, AXYZ-SF, AXYZ-ZB,
///   GXY-B1S, GXY-B2S, GXY-G4, GXY-RN, GXY-GD, GXY-GRW, SAGE.
inline constexpr std::string_view kGyroNsCtModelName = "gyro_ns_ct";

/// GYRO-NS-CT's sources other than GXY-RN, GXY-GD and GXY-GRW as a table (16 sources, the
/// OWSG magnitudes and modes), with the continuous start inclination of `terms`: the gyrocompass
/// terms GXY-B1S, GXY-B2S and GXY-G4 keep the initialising station's azimuth error through the
/// continuous survey. The first station's error turns half the first leg (not the Rev5 workbook
/// convention).
SurveyErrorModel gyro_ns_ct_table_model(const ContinuousGyroTerms& terms);

/// The OWSG stationary gyrocompass tool model GYRO-NS (rev 5; OWSG A020Gb, "OWSG Gyrocompass
/// Gyro"): a north-seeking x-y gyrocompass at every station, 18 sources in the OWSG order:
///   DRFR, DSFS, DSTG, SAGE, XYM1, XYM2, XYM3E, XYM4E, XCLA, XCLH, AXYZ-MIS, AXYZ-SF, AXYZ-ZB,
///   GXY-B1R, GXY-B2R, GXY-G1, GXY-G4, GXY-RN.
inline constexpr std::string_view kGyroNsModelName = "gyro_ns";

/// The OWSG gyro-while-drilling tool model GYRO-MWD (rev 5; OWSG A019Gb, "OWSG Gyro MWD"): a
/// gyrocompass at every station (taken at the connections), GYRO-NS's 18 sources with larger
/// GXY-G1, GXY-G4 and GXY-RN.
inline constexpr std::string_view kGyroMwdModelName = "gyro_mwd";

/// GYRO-NS as a table: the OWSG magnitudes (deg/h: GXY-B1R, GXY-B2R 0.15 random; GXY-G1 0.2,
/// GXY-G4 0.6 systematic; GXY-RN 0.4 random, noise reduction factor 1).
SurveyErrorModel gyro_ns_model();

/// GYRO-MWD as a table: GYRO-NS with GXY-G1 0.4, GXY-G4 1.0 and GXY-RN 0.6 deg/h.
SurveyErrorModel gyro_mwd_model();

/// Whether the model `name` gyrocompasses (gyro_ns_ct, gyro_ns, gyro_mwd): it uses the well's
/// latitude and Earth rate, and not its magnetic field.
bool is_gyro_tool_model(std::string_view name);

/// "mwd_rev5", "mwd_rev4", "gyro_ns_ct", "gyro_ns", "gyro_mwd".
std::span<const std::string> tool_model_names();

/// Throws ConfigError "<where> 'NAME': unknown survey error model; did you mean 'X'?" (or the
/// list of models) unless `name` is one of tool_model_names(). `where` names the option or
/// JSON pointer ("--model", "/survey/error_model").
void check_tool_model_name(std::string_view name, std::string_view where);

/// A title for messages: the MWD model's, or "OWSG GYRO-NS-CT (rev 5)", ...
std::string tool_model_title(std::string_view name);

/// The covariance of `stations` under the model `name` (checked as check_tool_model_name with
/// "--model"). `gyro` gives the continuous-gyro terms and the continuous start inclination
/// (used by gyro_ns_ct only; its other magnitudes are OWSG's; gyro_ns and gyro_mwd have OWSG's
/// magnitudes only). Throws as propagate_survey_errors and continuous_gyro_covariance (the
/// gyro models: every gyrocompass station below 90 deg inclination, a latitude below 90 deg, an
/// Earth rate > 0).
SurveyCovariance tool_model_covariance(std::string_view name,
                                       std::span<const ListingStation> stations,
                                       const WellParameters& well, const ContinuousGyroTerms& gyro);

}  // namespace stochnav::survey_error

#pragma once
// The ISCWSA MWD model tables (mwd_models.cpp), for error_model.cpp's lookup, and the rows
// the OWSG gyro tool model shares with them (gyro_models.cpp).

#include <initializer_list>
#include <numbers>
#include <vector>

#include "stochnav/survey_error/error_model.hpp"

namespace stochnav::survey_error {

/// 1 deg / 100 ft: the ISCWSA default tortuosity between stations (XCLA, XCLH).
inline constexpr double kIscwsaDefaultTortuosityRadPerM = std::numbers::pi / 180.0 / 30.48;

/// The depth terms DRFR, DSFS, DSTG: the same in Rev4, Rev5 and the OWSG gyro tool models.
std::vector<ErrorSource> iscwsa_depth_sources();
/// The Rev5 misalignment and tortuosity terms XYM1, XYM2, XYM3E, XYM4E, XCLA, XCLH (the same
/// in GYRO-NS-CT).
std::vector<ErrorSource> rev5_misalignment_sources();
/// The lists one after the other.
std::vector<ErrorSource> joined_sources(std::initializer_list<std::vector<ErrorSource>> lists);

/// ISCWSA MWD Rev5.11 (the Rev5 example workbook), 35 sources.
SurveyErrorModel make_mwd_rev5_model();
/// ISCWSA MWD Rev4, 27 sources.
SurveyErrorModel make_mwd_rev4_model();

}  // namespace stochnav::survey_error

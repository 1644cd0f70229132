#pragma once
// iscwsa_covariance.csv (DESIGN.md, `stochnav survey`): one row per station and error source,
// then the station's TOTAL, stations in listing order, sources in the model's order:
//   md_m,source,nn_m2,ee_m2,vv_m2,ne_m2,nv_m2,ev_m2
// NEV covariance elements in m^2 (error_propagation.hpp for the frame). Numbers are written
// in the shortest form that reads back to the same double.

#include <string>

#include "stochnav/survey_error/error_propagation.hpp"

namespace stochnav::survey_error {

inline constexpr char kCovarianceCsvHeader[] = "md_m,source,nn_m2,ee_m2,vv_m2,ne_m2,nv_m2,ev_m2";
inline constexpr char kTotalSourceName[] = "TOTAL";

/// The file's text, header included.
std::string covariance_csv(const SurveyCovariance& covariance);

}  // namespace stochnav::survey_error

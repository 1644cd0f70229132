#pragma once
// The ISCWSA MWD model tables (mwd_models.cpp), for error_model.cpp's lookup.

#include "stochnav/survey_error/error_model.hpp"

namespace stochnav::survey_error {

/// ISCWSA MWD Rev5.11 (the Rev5 example workbook), 35 sources.
SurveyErrorModel make_mwd_rev5_model();
/// ISCWSA MWD Rev4, 27 sources.
SurveyErrorModel make_mwd_rev4_model();

}  // namespace stochnav::survey_error

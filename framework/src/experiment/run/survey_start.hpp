#pragma once
// The survey's start in a navigation run: the tie-on (position, measured depth, attitude), the
// depth readings taken from the bit to the survey sensor, the tie-on MD checked against them,
// and the depth aid's stated sigma for the stations' md_sigma_m (experiment/survey.hpp,
// experiment/tally_smoother.hpp).

#include <optional>
#include <span>

#include "stochnav/experiment/survey.hpp"
#include "stochnav/experiment/tally_smoother.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav {

/// The sensor's measured depth (m) from a tally reading of the bit's (m): tally minus
/// "survey/sensor_to_bit_m".
double sensor_md_m(const plugin::RunConfig& config, double tally_md_m);

/// The tally at the start (m, the bit's depth): the mean of the "measured_depth_m" readings of
/// the aid data's leading rows flagged "zupt" (the tool at rest at the tie-on: one reading
/// would carry its full random error), else its first reading; nullopt without readings.
std::optional<double> tally_md_at_start_m(const plugin::AidData& aid_data);

/// Throws ConfigError naming "/initial_state/tie_on/measured_depth_m" when the configured
/// tie-on MD differs from the tally at the start, taken to the sensor, by more than
/// "survey/tie_on_md_tolerance_m". Nothing to check without a configured MD or readings.
void check_tie_on_against_tally(const plugin::RunConfig& config,
                                std::optional<double> tally_at_start_m);

/// The tie-on: the position of `start` (the state before alignment and any deliberate error);
/// MD as configured, else the tally at the start taken to the sensor, else 0; the hole's
/// direction from the configured initial attitude, else from `attitude` (the truth's first row
/// at a start from truth, the aligned state after an alignment: the tool sits at the tie-on).
SurveyTieOn survey_tie_on(const plugin::RunConfig& config, const NavState& start,
                          const NavState& attitude, std::optional<double> tally_at_start_m);

/// The stated 1-sigmas of the run's depth readings: the "pipe_length" aid's "sigma_random_m"
/// and "sigma_scale" (its defaults 0.05 m and 1e-3 where absent); nullopt without that aid.
std::optional<DepthReadingSigma> stated_depth_sigma(const plugin::RunConfig& config);

}  // namespace stochnav

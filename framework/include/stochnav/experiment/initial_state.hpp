#pragma once
// The start of a navigation run from the run config's "initial_state" and "initial_error"
// sections (plugin/run_config.hpp): the known state at the tie-on, the static alignment, and
// the deliberate initial error. `stochnav run` starts this way; an embedder driving MwdNavigator
// from its own loop calls the same functions:
//   start = state_from_initial_config(*config.initial_state, t0)   (or truth's first row,
//                                                                   nav_state_from_truth_row)
//   [aligned = align_at_rest(span, start, alignment, config.filter.options, gyro, accel)]
//   filter = filter_start(config, start or aligned.state, options or aligned.options)
//   MwdNavigator navigator(filter.estimate, gyro, accel, aids, filter.options);

#include <span>

#include "stochnav/filter/filter_options.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav {

/// The tie-on position with the configured attitude (identity when aligning) and velocity, at
/// time t_s.
NavState state_from_initial_config(const plugin::InitialStateConfig& config, double t_s);

/// Checks that the span is static (AlignmentConfig's spreads over 1-s blocks) and that it is as
/// long as static_s. Throws ConfigError naming /initial_state/alignment/static_s with the
/// measured numbers and the fix.
void check_static_span(std::span<const ImuIncrement> span, const plugin::AlignmentConfig& config,
                       double record_start_s);

struct AlignedStart {
  NavState state;         ///< at the end of the span, zero velocity, the aligned attitude
  FilterOptions options;  ///< `options` with the alignment's bias estimates and 1-sigmas
};

/// Coarse alignment (levelling + gyrocompassing) over the span, then fine alignment: the
/// navigation filter over the same span with zero-velocity and known-position updates at 1 Hz
/// (AlignmentConfig's sigmas), from `site` (the tie-on; its attitude is ignored). The returned
/// options carry the estimated biases (initial_*_bias) and the fine alignment's 1-sigmas of
/// position, velocity, attitude and biases as the run's initial sigmas.
AlignedStart align_at_rest(std::span<const ImuIncrement> span, const NavState& site,
                           const plugin::AlignmentConfig& config, const FilterOptions& options,
                           plugin::NoiseModelPlugin& gyro_noise,
                           plugin::NoiseModelPlugin& accel_noise);

/// Puts the configured error into the initial estimate (InitialErrorConfig's conventions): the
/// state's position, velocity and attitude, and the options' initial bias estimates. The drawn
/// part uses the options' initial sigmas as they are on entry.
void apply_initial_error(const plugin::InitialErrorConfig& error, NavState& state,
                         FilterOptions& options);

/// What MwdNavigator starts from: the initial estimate and the filter options.
struct FilterStart {
  NavState estimate;      ///< the start with the configured initial error
  FilterOptions options;  ///< with the error's initial bias estimates
};

/// A run config's filter start from a known start state and its options (config.filter.options,
/// or align_at_rest's): the configured "initial_error" applied (apply_initial_error), if any.
FilterStart filter_start(const plugin::RunConfig& config, const NavState& start,
                         const FilterOptions& options);

}  // namespace stochnav

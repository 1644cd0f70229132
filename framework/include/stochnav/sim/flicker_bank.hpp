#pragma once
// Bias instability (flicker rate noise) as a bank of independent Gauss-Markov processes.
//
// Method: correlation times T_k log-spaced two per decade from 0.1 tau0 to 3 band_max_s; their
// variances s_k^2 are the non-negative least-squares solution (Lawson-Hanson) that makes the
// bank's exact Allan variance, sum_k AVAR_GM(s_k, T_k; tau), equal to the flicker floor
// (2 ln 2 / pi) B^2 at 20 log-spaced taus per decade over [tau0, band_max_s]. Over that band the
// floor is flat to better than 1e-3 relative (max_relative_ripple reports the achieved value,
// typically ~1e-4); outside it the bank's AVAR falls off (as tau for tau << tau0, 1/tau for
// tau >> band_max_s). Each component is simulated exactly (sim/noise_generator.hpp), so
// flicker_bank_allan_variance is the exact Allan variance of the simulated records.

#include <vector>

namespace stochnav {

struct FlickerBank {
  std::vector<double> tau_c_s;       ///< correlation time of each component (s), ascending
  std::vector<double> sigma;         ///< stationary standard deviation of each component, signal
  double band_min_s = 0.0;           ///< tau0: the band over which the floor is flat (s)
  double band_max_s = 0.0;           ///< (s)
  double max_relative_ripple = 0.0;  ///< max |AVAR_bank / floor - 1| over the band
};

/// Default density of the bank's correlation times: what the simulator uses.
inline constexpr double kFlickerComponentsPerDecade = 2.0;

/// Designs the bank for coefficient b (natural units, >= 0), sampling interval tau0_s (> 0) and
/// flat band up to band_max_s (>= tau0_s; smaller values are raised to tau0_s). b = 0 gives an
/// empty bank. components_per_decade (> 0) sets the spacing of the candidate correlation times;
/// below the default the floor ripples more (max_relative_ripple says how much), which is how a
/// filter may trade states for flatness (model/shaping_filter.hpp).
FlickerBank design_flicker_bank(double b, double tau0_s, double band_max_s,
                                double components_per_decade = kFlickerComponentsPerDecade);

/// Exact Allan variance of the bank at tau_s (s, > 0), signal^2.
double flicker_bank_allan_variance(const FlickerBank& bank, double tau_s);

}  // namespace stochnav

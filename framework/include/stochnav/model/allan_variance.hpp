#pragma once
// Closed-form Allan variance of noise terms and models (DESIGN.md table), in natural units.

#include "stochnav/model/noise_model.hpp"
#include "stochnav/model/noise_term.hpp"

namespace stochnav {

/// Allan variance of one term at averaging time tau_s (s, > 0), in signal^2 of the natural unit
/// ((rad/s)^2 for gyros). Nonstationary terms contribute 0. NaN if tau_s <= 0 or not finite.
double allan_variance(const NoiseTerm& term, double tau_s);

/// Sum over the model's terms (independent processes add in Allan variance).
double allan_variance(const NoiseModel& model, double tau_s);

}  // namespace stochnav

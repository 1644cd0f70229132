#pragma once
// Where the record leaves the model and what the departure looks like (DESIGN.md, workflow step
// 4): the tau range, and the shape of the excess Allan variance there, read against the
// vocabulary.
//
// Range: the contiguous run of octave points around the largest |z| (diagnose/gap.hpp) with
// |z| > 2. Excess: e(tau) = A(tau) - mu(tau) at the dense taus inside the range widened by two
// octaves each side (one octave for the slope). Shape, in this order:
//   sinusoid          e has a null (a local minimum below 1/4 of the maxima on both sides)
//                     with a rising excess before it: the sin^4(pi f tau) pattern, nulls at k/f;
//   gauss_markov      a single bump: e rises then falls by more than a factor 2 inside the
//                     widened range;
//   otherwise by the log-log slope s of e over the range:
//     s < -1.5 quantization, < -0.5 angle_random_walk, < 0.5 bias_instability (flat floor),
//     < 1.5 rate_random_walk, else rate_ramp.
// A record below the model's band has no excess: the signature then says so, and names the term
// the slope of the deficit points at (the model has too much of it).

#include <array>
#include <optional>
#include <span>
#include <string>

#include "stochnav/diagnose/gap.hpp"
#include "stochnav/model/noise_model.hpp"

namespace stochnav {

struct Signature {
  bool found = false;  ///< some octave point has |z| > 2
  bool above = true;   ///< the record lies above the model there
  std::optional<std::array<double, 2>> tau_range_s;
  double max_abs_z = 0.0;
  double tau_at_max_s = 0.0;
  double slope = 0.0;  ///< log-log slope of the excess AVAR over the range
  TermType suggested = TermType::kAngleRandomWalk;  ///< the vocabulary name of the shape
  std::string shape;  ///< "slope -1.9", "single bump", "null at 0.053 s", ...
};

/// Reads the signature of `gap` (octave points) with the dense measured curve (tau_s, avar in
/// natural units, edf of each point) and the model (its stationary equivalent). Only dense
/// points whose excess is significant (above 3 sqrt(2 / edf) times the model's AVAR) shape the
/// slope and the null test.
Signature read_signature(const AvarGap& gap, std::span<const double> dense_tau_s,
                         std::span<const double> dense_avar, std::span<const double> dense_edf,
                         const NoiseModel& model);

}  // namespace stochnav

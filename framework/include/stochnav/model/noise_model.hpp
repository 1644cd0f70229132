#pragma once
// A noise model: the signal unit, a nominal sampling rate and a list of noise terms. A plain
// value type; build it in code or with noise_model_from_json (model/noise_model_json.hpp).

#include <optional>
#include <string>
#include <vector>

#include "stochnav/core/units.hpp"
#include "stochnav/model/noise_term.hpp"

namespace stochnav {

struct NoiseModel {
  Unit unit = Unit::kPlain;  ///< unit the signal is written in (fixes the reporting units)
  double rate_hz = 0.0;      ///< nominal sampling rate (Hz), > 0
  std::vector<NoiseTerm> terms;  ///< in the order given; at most one nonstationary term
};

/// One violated rule of a model, located by a JSON pointer relative to the model object
/// (e.g. "/terms/1/N"), with the expected form; values are quoted in reporting units.
struct ModelIssue {
  std::string pointer;
  std::string problem;
  std::string expected;
};

/// The first rule `model` breaks, or nullopt when valid: rate_hz > 0 and finite; coefficients
/// finite and in the range of parameter_specs; segments ascending, non-overlapping, start >= 0,
/// end > start, scale >= 0, at least one; at most one nonstationary term.
std::optional<ModelIssue> find_model_issue(const NoiseModel& model);

/// Same types, same segments, every parameter within rel_tol (|a - b| <= rel_tol max(|a|, |b|)),
/// optional phases both absent or both within rel_tol.
bool equals(const NoiseTerm& a, const NoiseTerm& b, double rel_tol = 1e-9);

/// Same unit, rate_hz within rel_tol and equal terms in the same order.
bool equals(const NoiseModel& a, const NoiseModel& b, double rel_tol = 1e-9);

/// One line per term with the coefficients in reporting units, e.g.
/// "angle_random_walk: N = 0.05 deg/sqrt(h)"; sigma_natural (same type, 1-sigma values) adds
/// " +/- x" to each parameter.
std::string describe(const NoiseTerm& term, Quantity quantity,
                     const NoiseTerm* sigma_natural = nullptr);

/// A header line "noise model: deg/h at 100 Hz, 3 terms" followed by describe() of each term.
std::string describe(const NoiseModel& model);

}  // namespace stochnav

#pragma once
// The steering keys of a noise plugin's fit options (beside "method", "terms", ...): starting
// values, fixed parameters and search ranges, named as `stochnav fit --start/--fix/--bound` name
// them (fit/parameter_control_names.hpp), values in the reporting units of the sensor group:
//   "start": {"gauss_markov#2.tau_c": 100},
//   "fix":   {"gauss_markov.tau_c": 300},
//   "bound": {"gauss_markov#2.tau_c": [5, 500]}      ([LOW, HIGH])
// Without #K a name is the first term of its type. term_fit_table() adds "method" ("avar" |
// "gmwm") to them: the fit options the in-tree fitters (white, gauss_markov, augmented) share. Bad
// keys or values are ConfigErrors naming the JSON pointer of the entry
// (".../fix/gauss_markov.tau_c: ..."), so a run exits 2 with one line.

#include <span>
#include <vector>

#include "stochnav/fit/parameter_control_names.hpp"
#include "stochnav/plugin/calibration_fit.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/param_table.hpp"

namespace stochnav::plugin {

/// The entries as given (reporting units; each ControlItem::where its JSON pointer).
struct FitSteering {
  std::vector<ControlItem> start;
  std::vector<ControlItem> fix;
  std::vector<ControlItem> bound;

  bool empty() const { return start.empty() && fix.empty() && bound.empty(); }

  /// The controls of a fit of `terms` to a record of `group` (FitOptions::controls), checked by
  /// check_parameter_controls. Throws ConfigError "<pointer>/<key>[/<name>]: why; how".
  std::vector<ParameterControl> controls(std::span<const TermType> terms, SensorGroup group) const;

 private:
  /// The JSON pointer of the entry an issue is about (of its key when not one entry's).
  std::string issue_pointer(const ParameterControlIssue& issue) const;
};

/// The keys "start", "fix" and "bound" (each optional, default {}).
const ParamTable<FitSteering>& fit_steering_table();

/// What every in-tree fitter of noise terms takes besides its own keys: the estimator and the
/// steering.
struct TermFitOptions {
  CalibrationEstimator method = CalibrationEstimator::kAllanVariance;  ///< "method"
  FitSteering steering;                                                ///< "start", "fix", "bound"
};

/// The keys "method" ("avar" default, or "gmwm"), "start", "fix" and "bound", for a fitter's
/// table: kMyFitTable.plus(lift(&MyFitOptions::fit, term_fit_table())).
const ParamTable<TermFitOptions>& term_fit_table();

}  // namespace stochnav::plugin

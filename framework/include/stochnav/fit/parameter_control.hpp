#pragma once
// Steering a fit's parameters: starting values, fixed (held) values and search ranges per
// parameter of a given term list. One representation for both estimators, the Allan-variance
// fit (FitOptions::controls, fit/fit_noise_terms.hpp) and GMWM (GmwmOptions::controls,
// fit/gmwm_fit.hpp), built from text by the CLI (fit/parameter_control_names.hpp) and from JSON
// by the noise plugins' fitters (plugin/fit_steering.hpp).
//
// A fixed parameter is not fitted: it keeps its value, its 1-sigma uncertainty is reported as 0
// and it does not count in FitDiagnostics::parameters. A parameter on a bound the user gave is
// the user's constraint, not a failed parameter: it is not in FitDiagnostics::at_bound (a warning
// names it); its uncertainty is that of the fit with the bound as given.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochnav/model/noise_term.hpp"

namespace stochnav {

/// Steering of one parameter of one term (all natural units). term: index into the term list
/// (FitOptions::terms, GmwmOptions::terms); parameter: index into parameter_specs(type).
struct ParameterControl {
  std::size_t term = 0;
  std::size_t parameter = 0;
  std::optional<double> start;  ///< starting value, > 0 (replaces the start search for it)
  std::optional<double> fixed;  ///< held at this value, > 0 (not fitted)
  std::optional<double> lower;  ///< search range, 0 < lower < upper (replaces the default)
  std::optional<double> upper;
};

/// "gauss_markov.tau_c", or "gauss_markov#2.tau_c" (K from 1) when the type repeats in `terms`:
/// the spelling of --start/--fix/--bound and of the plugins' "start"/"fix"/"bound" keys.
std::string parameter_label(std::span<const TermType> terms, std::size_t term,
                            std::size_t parameter);

/// The warning for a parameter left on a bound the user gave (`label`: parameter_label).
std::string on_bound_given_warning(std::string_view label);

/// What is wrong with a set of controls, in parts each front end words its own way: the CLI as
/// "--<key> <label>: <reason>", a plugin as "<pointer>/<key>/<label>: <reason>".
struct ParameterControlIssue {
  std::string key;     ///< "start", "fix" or "bound"
  std::string label;   ///< parameter_label; empty when the issue is not one parameter's
  std::string reason;  ///< why, and how to fix it
  /// "<key> <label>: <reason>" ("<key>: <reason>" without a label).
  std::string message() const;
};

/// The first problem of `controls` for a fit of `terms`: a term or parameter index out of range
/// or not fitted (the sinusoid phase), a value not finite and > 0, lower >= upper, a start or
/// fixed value outside its bounds, every parameter fixed, or two Gauss-Markov terms started or
/// fixed at the same tau_c (unidentifiable). nullopt when they are usable.
std::optional<ParameterControlIssue> check_parameter_controls(
    std::span<const TermType> terms, std::span<const ParameterControl> controls);

/// A term list and its controls after dropping some terms: the controls of dropped terms go,
/// the others follow their term to its new index.
struct SteeredTerms {
  std::vector<TermType> terms;
  std::vector<ParameterControl> controls;
};

/// `terms` without those whose `drop` flag is set (drop.size() == terms.size()).
SteeredTerms without_terms(std::span<const TermType> terms,
                           std::span<const ParameterControl> controls,
                           const std::vector<bool>& drop);

}  // namespace stochnav

#include "stochnav/fit/parameter_control.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace stochnav {

std::string parameter_label(std::span<const TermType> terms, std::size_t term,
                            std::size_t parameter) {
  const TermType type = terms[term];
  const std::string_view name = parameter_specs(type)[parameter].name;
  if (std::count(terms.begin(), terms.end(), type) < 2) {
    return fmt::format("{}.{}", term_type_name(type), name);
  }
  const auto occurrence = std::count(terms.begin(), terms.begin() + static_cast<long>(term), type);
  return fmt::format("{}#{}.{}", term_type_name(type), occurrence + 1, name);
}

std::string on_bound_given_warning(std::string_view label) {
  return fmt::format(
      "{} is on the bound given for it: the data would move it further "
      "(its uncertainty holds with the bound in place)",
      label);
}

std::string ParameterControlIssue::message() const {
  return label.empty() ? fmt::format("{}: {}", key, reason)
                       : fmt::format("{} {}: {}", key, label, reason);
}

std::optional<ParameterControlIssue> check_parameter_controls(
    std::span<const TermType> terms, std::span<const ParameterControl> controls) {
  std::vector<double> given_tau;
  std::size_t fixed = 0;
  for (const ParameterControl& c : controls) {
    const std::string key = c.fixed ? "fix" : c.start ? "start" : "bound";
    if (c.term >= terms.size() || c.parameter >= parameter_specs(terms[c.term]).size()) {
      return ParameterControlIssue{key, "", "names a term or parameter the model does not have"};
    }
    const std::string label = parameter_label(terms, c.term, c.parameter);
    if (parameter_specs(terms[c.term])[c.parameter].optional) {
      return ParameterControlIssue{key, label, "is not fitted; steer another parameter"};
    }
    const std::pair<const char*, std::optional<double>> values[] = {
        {"start", c.start}, {"fix", c.fixed}, {"bound", c.lower}, {"bound", c.upper}};
    for (const auto& [value_key, value] : values) {
      if (value && !(*value > 0.0 && std::isfinite(*value))) {
        return ParameterControlIssue{value_key, label, "is not > 0; give a finite value > 0"};
      }
    }
    if (c.lower && c.upper && !(*c.lower < *c.upper)) {
      return ParameterControlIssue{"bound", label, "LOW is not below HIGH; give LOW < HIGH"};
    }
    for (const auto& [value_key, value] : {values[0], values[1]}) {
      if (value && ((c.lower && *value < *c.lower) || (c.upper && *value > *c.upper))) {
        return ParameterControlIssue{value_key, label,
                                     "is outside its bound; give a value within LOW:HIGH"};
      }
    }
    if (c.fixed) ++fixed;
    if (terms[c.term] == TermType::kGaussMarkov && c.parameter == 1) {
      const auto tau = c.fixed ? c.fixed : c.start;
      if (!tau) continue;
      if (std::find(given_tau.begin(), given_tau.end(), *tau) != given_tau.end()) {
        return ParameterControlIssue{
            key, label,
            fmt::format("two gauss_markov terms at tau_c = {:g} s are not identifiable (they "
                        "would stay equal); give distinct tau_c",
                        *tau)};
      }
      given_tau.push_back(*tau);
    }
  }
  std::size_t fitted = 0;
  for (TermType type : terms) {
    for (const ParameterSpec& spec : parameter_specs(type)) fitted += spec.optional ? 0 : 1;
  }
  if (fitted > 0 && fixed >= fitted) {
    return ParameterControlIssue{"fix", "",
                                 "every parameter of the model is fixed, nothing is left to fit; "
                                 "leave at least one free"};
  }
  return std::nullopt;
}

SteeredTerms without_terms(std::span<const TermType> terms,
                           std::span<const ParameterControl> controls,
                           const std::vector<bool>& drop) {
  SteeredTerms kept;
  std::vector<std::size_t> new_index(terms.size(), terms.size());
  for (std::size_t t = 0; t < terms.size(); ++t) {
    if (drop[t]) continue;
    new_index[t] = kept.terms.size();
    kept.terms.push_back(terms[t]);
  }
  for (ParameterControl control : controls) {
    if (control.term >= terms.size() || new_index[control.term] == terms.size()) continue;
    control.term = new_index[control.term];
    kept.controls.push_back(control);
  }
  return kept;
}

}  // namespace stochnav

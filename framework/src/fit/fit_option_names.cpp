#include "stochnav/fit/fit_option_names.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "stochnav/core/errors.hpp"

namespace stochnav {

std::vector<TermType> parse_fit_terms(std::span<const std::string> names, std::string_view option) {
  const std::string label(option);
  std::vector<TermType> terms;
  for (const std::string& name : names) {
    if (name.empty()) continue;
    const auto type = parse_term_type(name);
    if (!type) {
      std::string known;
      for (TermType t : all_term_types()) {
        known += (known.empty() ? "" : ", ") + std::string(term_type_name(t));
      }
      throw ConfigError(label + ": unknown term '" + name + "'; use a comma-separated list of " +
                        known);
    }
    // Two power-law terms of one type are one term with a degenerate split between them; two
    // Gauss-Markov or sinusoid terms are two different processes.
    const bool repeatable = *type == TermType::kGaussMarkov || *type == TermType::kSinusoid;
    if (!repeatable && std::find(terms.begin(), terms.end(), *type) != terms.end()) {
      throw ConfigError(label + ": " + name + " is given twice; name each power-law term once " +
                        "(only gauss_markov and sinusoid may repeat)");
    }
    terms.push_back(*type);
  }
  if (terms.empty()) {
    throw ConfigError(label + ": no term named; give a comma-separated list of terms, or leave " +
                      "out " + label + " to choose them automatically");
  }
  return terms;
}

std::vector<std::string> split_comma_list(std::string_view list) {
  std::vector<std::string> items;
  std::stringstream stream{std::string(list)};
  std::string item;
  while (std::getline(stream, item, ',')) items.push_back(item);
  return items;
}

RobustLoss parse_robust_loss(std::string_view text, std::string_view option) {
  if (text == "huber") return RobustLoss::kHuber;
  if (text == "cauchy") return RobustLoss::kCauchy;
  if (text == "none") return RobustLoss::kNone;
  throw ConfigError(std::string(option) + " '" + std::string(text) +
                    "': use huber, cauchy or none");
}

InformationCriterion parse_information_criterion(std::string_view text, std::string_view option) {
  if (text == "bic") return InformationCriterion::kBic;
  if (text == "aic") return InformationCriterion::kAic;
  throw ConfigError(std::string(option) + " '" + std::string(text) + "': use bic or aic");
}

GaussMarkovSampling parse_gauss_markov_sampling(std::string_view text, std::string_view option) {
  if (text == "mean") return GaussMarkovSampling::kIntervalMean;
  if (text == "point") return GaussMarkovSampling::kPoint;
  throw ConfigError(
      fmt::format("{} '{}': use mean (samples are interval means) or point (a "
                  "discrete AR1, the R gmwm package's)",
                  option, text));
}

}  // namespace stochnav

#pragma once
// The names a user gives a fit's options by (term lists, robust loss, information criterion),
// parsed and checked in one place for every front end: the CLI (`stochnav fit --terms ...`) and
// the Python module (`stochnav.fit(..., terms=[...])`). `option` is how the front end spells the
// option ("--terms", "terms"); every error is one ConfigError line starting with it.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochnav/fit/fit_noise_terms.hpp"
#include "stochnav/model/noise_term.hpp"

namespace stochnav {

/// The term types named in `names` (term_type_name spellings, in order; empty names are
/// skipped). Throws ConfigError "<option>: unknown term 'x'; use a comma-separated list of ..."
/// for an unknown name, "<option>: <name> is given twice; ..." for a power-law term named twice
/// (only gauss_markov and sinusoid may repeat: two of them are two processes), and
/// "<option>: no term named; ..." when no name is left.
std::vector<TermType> parse_fit_terms(std::span<const std::string> names, std::string_view option);

/// The items of a comma-separated list, as typed ("a,b,,c" gives "a", "b", "", "c").
std::vector<std::string> split_comma_list(std::string_view list);

/// "huber", "cauchy" or "none"; otherwise ConfigError "<option> 'x': use huber, cauchy or none".
RobustLoss parse_robust_loss(std::string_view text, std::string_view option);

/// "bic" or "aic"; otherwise ConfigError "<option> 'x': use bic or aic".
InformationCriterion parse_information_criterion(std::string_view text, std::string_view option);

/// "mean" or "point" (fit/implied_wavelet_variance.hpp); otherwise ConfigError
/// "<option> 'x': use mean (...) or point (...)".
GaussMarkovSampling parse_gauss_markov_sampling(std::string_view text, std::string_view option);

}  // namespace stochnav

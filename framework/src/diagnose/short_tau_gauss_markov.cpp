#include "stochnav/diagnose/short_tau_gauss_markov.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <exception>

#include "stochnav/fit/gmwm_fit.hpp"
#include "stochnav/fit/implied_wavelet_variance.hpp"
#include "stochnav/model/allan_variance.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

bool is_short_gauss_markov(const NoiseTerm& term, double tau0) {
  const auto* gm = std::get_if<GaussMarkovTerm>(&term);
  return gm != nullptr && gm->tau_c <= kShortTauMaxSamples * tau0 * (1.0 + 1e-9);
}

// The measured wavelet variance with the held terms' implied wavelet variance taken off; levels
// left <= 0 are dropped. The interval moves with the value (its width, which sets Omega, stays).
GmwmData without_held_terms(const GmwmData& data, const std::vector<NoiseTerm>& held) {
  if (held.empty()) return data;
  GmwmData out = data;
  out.scale_s.clear();
  out.wv.clear();
  out.wv_lo.clear();
  out.wv_hi.clear();
  for (std::size_t j = 0; j < data.scale_s.size(); ++j) {
    double fixed = 0.0;
    for (const NoiseTerm& term : held) fixed += 0.5 * allan_variance(term, 0.5 * data.scale_s[j]);
    const double value = data.wv[j] - fixed;
    if (!(value > 0.0) || !(data.wv_lo[j] - fixed > 0.0)) continue;
    out.scale_s.push_back(data.scale_s[j]);
    out.wv.push_back(value);
    out.wv_lo.push_back(data.wv_lo[j] - fixed);
    out.wv_hi.push_back(data.wv_hi[j] - fixed);
  }
  return out;
}

// The Gauss-Markov term of `fitted` with the shortest tau_c inside [lower, upper] (relative
// slack 1e-6), with its index; -1 when none.
std::ptrdiff_t new_short_term(const FitResult& fitted, double lower, double upper) {
  std::ptrdiff_t best = -1;
  double best_tau = 0.0;
  for (std::size_t i = 0; i < fitted.model.terms.size(); ++i) {
    const auto* gm = std::get_if<GaussMarkovTerm>(&fitted.model.terms[i]);
    if (gm == nullptr || gm->tau_c < lower * (1.0 - 1e-6) || gm->tau_c > upper * (1.0 + 1e-6)) {
      continue;
    }
    if (best < 0 || gm->tau_c < best_tau) {
      best = static_cast<std::ptrdiff_t>(i);
      best_tau = gm->tau_c;
    }
  }
  return best;
}

double lag1_of_model(const NoiseModel& model) {
  const double c0 = sampled_autocovariance(model, 0, GaussMarkovSampling::kIntervalMean);
  const double c1 = sampled_autocovariance(model, 1, GaussMarkovSampling::kIntervalMean);
  return c0 > 0.0 ? c1 / c0 : 0.0;
}

}  // namespace

ShortTauGaussMarkovCheck check_short_tau_gauss_markov(const GmwmData& data, bool robust,
                                                      const NoiseModel& model, double lag1_record,
                                                      const ShortTauOptions& options) {
  ShortTauGaussMarkovCheck check;
  check.robust = robust;
  check.lag1_record = lag1_record;
  const double tau0 = 1.0 / data.rate_hz;
  std::vector<NoiseTerm> held;
  for (const NoiseTerm& term : model.terms) {
    const TermType type = term_type(term);
    if (type == TermType::kNonstationary) {
      check.not_applicable =
          "the model has a nonstationary term: the stationary wavelet variance does not describe "
          "it";
      return check;
    }
    if (is_short_gauss_markov(term, tau0)) {
      check.in_model = true;
      continue;
    }
    if (type == TermType::kSinusoid) {
      held.push_back(term);
      continue;
    }
    if (!has_wavelet_variance_form(type)) continue;
    if (type != TermType::kGaussMarkov &&
        std::find(check.base_terms.begin(), check.base_terms.end(), type) !=
            check.base_terms.end()) {
      continue;
    }
    check.base_terms.push_back(type);
  }
  if (std::find(check.base_terms.begin(), check.base_terms.end(), TermType::kAngleRandomWalk) ==
      check.base_terms.end()) {
    check.base_terms.push_back(TermType::kAngleRandomWalk);
  }
  const GmwmData fitted_data = without_held_terms(data, held);
  check.scales = fitted_data.scale_s.size();
  const double lower = kGmwmMinCorrelationTimeSamples * tau0;
  const double upper = kShortTauMaxSamples * tau0;
  FitResult without, with;
  try {
    GmwmOptions base;
    base.terms = check.base_terms;
    base.drop_terms_at_bound = true;
    without = fit_gmwm(fitted_data, base);
    GmwmOptions extended = base;
    extended.terms.push_back(TermType::kGaussMarkov);
    ParameterControl range;
    range.term = extended.terms.size() - 1;
    range.parameter = 1;  // tau_c
    range.lower = lower;
    range.upper = upper;
    range.start = std::sqrt(lower * upper);
    extended.controls.push_back(range);
    with = fit_gmwm(fitted_data, extended);
  } catch (const std::exception& error) {
    check.not_applicable =
        std::string("the wavelet-variance fit could not be made: ") + error.what();
    return check;
  }
  check.applicable = true;
  check.objective_without = without.diagnostics.chi_square;
  check.objective_with = with.diagnostics.chi_square;
  check.threshold = boost::math::quantile(boost::math::chi_squared_distribution<double>(2.0),
                                          1.0 - options.alpha);
  check.significant = check.objective_without - check.objective_with > check.threshold;
  check.fitted = with.model;
  check.lag1_model = lag1_of_model(with.model);
  const std::ptrdiff_t index = new_short_term(with, lower, upper);
  if (index < 0) return check;  // dropped: nothing short in the record
  const auto i = static_cast<std::size_t>(index);
  check.term = with.model.terms[i];
  const auto& gm = std::get<GaussMarkovTerm>(check.term);
  if (i < with.sigma.size()) {
    if (const auto* s = std::get_if<GaussMarkovTerm>(&with.sigma[i])) {
      check.sigma_sigma = s->sigma;
      check.tau_c_sigma = s->tau_c;
    }
  }
  check.at_lower_end = gm.tau_c <= lower * 1.01;
  check.at_upper_end = gm.tau_c >= upper * 0.99;
  for (double scale : fitted_data.scale_s) {
    const double total =
        implied_wavelet_variance(with.model, scale, GaussMarkovSampling::kIntervalMean);
    const double own =
        implied_wavelet_variance(check.term, scale, tau0, GaussMarkovSampling::kIntervalMean);
    if (total > 0.0 && own / total > check.largest_share) {
      check.largest_share = own / total;
      check.largest_share_scale_s = scale;
    }
  }
  check.named =
      check.significant && !check.at_upper_end && check.largest_share >= options.min_term_share;
  return check;
}

std::string ShortTauGaussMarkovCheck::summary(Unit unit) const {
  if (!applicable)
    return "Short-tau Gauss-Markov check (wavelet variance) not made: " + not_applicable + ".";
  const Quantity quantity = quantity_of(unit);
  const auto& gm = std::get<GaussMarkovTerm>(term);
  const double tau0 = fitted.rate_hz > 0.0 ? 1.0 / fitted.rate_hz : 0.0;
  const std::string wv =
      robust ? "robust Haar wavelet variance (outliers flagged)" : "Haar wavelet variance";
  const std::string drop = fmt::format(
      "GMWM objective {:.4g} -> {:.4g} over {} scales with a Gauss-Markov term of tau_c <= {:g} "
      "samples (threshold {:.3g}, chi2_2)",
      objective_without, objective_with, scales, kShortTauMaxSamples, threshold);
  if (!named) {
    std::string why;
    if (!significant) {
      why = "the drop is not significant";
    } else if (gm.tau_c <= 0.0) {
      why = "the fit dropped the term";
    } else if (at_upper_end) {
      why = fmt::format(
          "its tau_c ends on the upper end of the range searched ({:.3g} s): not a short-tau term",
          gm.tau_c);
    } else {
      why =
          fmt::format("it makes up at most {:.0f} % of the model's wavelet variance (at {:.3g} s)",
                      100.0 * largest_share, largest_share_scale_s);
    }
    return fmt::format("No short-tau Gauss-Markov term in the {}: {}; {}.", wv, drop, why);
  }
  const double sigma = to_reported(quantity, ParameterDimension::kRate, gm.sigma);
  const double sigma_sigma_reported = to_reported(quantity, ParameterDimension::kRate, sigma_sigma);
  const std::string sigma_unit = reported_unit_name(quantity, ParameterDimension::kRate);
  return fmt::format(
      "Short-tau Gauss-Markov (AR1) term named from the {}: gauss_markov sigma = {:.4g} +/- "
      "{:.2g} {}, tau_c = {:.3g} +/- {:.2g} s ({:.2f} sampling intervals{}); {}. It makes up "
      "{:.0f} % of the model's wavelet variance at {:.3g} s; the fitted terms give a lag-1 "
      "correlation of {:.3f} (the record's: {:.3f}). The Allan variance smears this below one "
      "sample{}. What to do: add the term (or fit with `stochnav fit --method gmwm --terms "
      "...,gauss_markov`).",
      wv, sigma, sigma_sigma_reported, sigma_unit, gm.tau_c, tau_c_sigma,
      tau0 > 0.0 ? gm.tau_c / tau0 : 0.0,
      at_lower_end ? "; flagged: on the lower end of the range searched, a correlation time of "
                     "this order or shorter, not an estimate"
                   : "",
      drop, 100.0 * largest_share, largest_share_scale_s, lag1_model, lag1_record,
      in_model ? "; the model's own short Gauss-Markov term (from the Allan fits, which stop "
                 "at tau_c = one sample) is this one, placed here"
               : "");
}

}  // namespace stochnav

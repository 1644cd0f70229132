#include "stochnav/model/shaping_filter.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>
#include <variant>

#include "stochnav/core/errors.hpp"
#include "stochnav/sim/flicker_bank.hpp"

namespace stochnav {
namespace {

void add_first_order(ShapingFilter& filter, double sigma, double tau_c,
                     const ShapingOptions& options) {
  if (!(sigma > 0.0)) return;
  if (tau_c < options.fold_below_s) {
    filter.white_psd += 2.0 * sigma * sigma * tau_c;
  } else {
    filter.first_order.push_back({sigma, tau_c});
  }
}

}  // namespace

std::string ShapingOptions::validate() const {
  if (!(tau0_s > 0.0) || !std::isfinite(tau0_s)) return "tau0_s must be > 0";
  if (!(flicker_band_max_s >= tau0_s) || !std::isfinite(flicker_band_max_s)) {
    return "flicker_band_max_s must be >= tau0_s";
  }
  if (!(flicker_components_per_decade > 0.0) || !std::isfinite(flicker_components_per_decade)) {
    return "flicker_components_per_decade must be > 0";
  }
  if (!(fold_below_s >= 0.0) || !std::isfinite(fold_below_s)) return "fold_below_s must be >= 0";
  return {};
}

int ShapingFilter::size() const {
  return static_cast<int>(first_order.size() + 2 * ramp_sigma.size() + 2 * oscillators.size());
}

void ShapingFilter::transition(double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                               Eigen::Ref<Eigen::MatrixXd> q_d) const {
  phi.setZero();
  q_d.setZero();
  int i = 0;
  for (const FirstOrderState& state : first_order) {
    phi(i, i) = std::exp(-dt_s / state.tau_c);
    // 1 - exp(-2 dt / tau) without cancellation for small steps.
    q_d(i, i) = state.sigma * state.sigma * -std::expm1(-2.0 * dt_s / state.tau_c);
    ++i;
  }
  for (std::size_t r = 0; r < ramp_sigma.size(); ++r) {
    phi(i, i) = 1.0;
    phi(i, i + 1) = dt_s;
    phi(i + 1, i + 1) = 1.0;
    i += 2;
  }
  for (const OscillatorState& oscillator : oscillators) {
    const double angle = 2.0 * std::numbers::pi * oscillator.frequency_hz * dt_s;
    const double c = std::cos(angle), s = std::sin(angle);
    phi(i, i) = c;
    phi(i, i + 1) = -s;
    phi(i + 1, i) = s;
    phi(i + 1, i + 1) = c;
    i += 2;
  }
}

void ShapingFilter::initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const {
  p0.setZero();
  int i = 0;
  for (const FirstOrderState& state : first_order) {
    p0(i, i) = state.sigma * state.sigma;
    ++i;
  }
  for (double sigma : ramp_sigma) {
    p0(i + 1, i + 1) = sigma * sigma;
    i += 2;
  }
  for (const OscillatorState& oscillator : oscillators) {
    const double variance = 0.5 * oscillator.amplitude * oscillator.amplitude;
    p0(i, i) = variance;
    p0(i + 1, i + 1) = variance;
    i += 2;
  }
}

void ShapingFilter::sensor_map(Eigen::Ref<Eigen::MatrixXd> map_row) const {
  map_row.setZero();
  int i = 0;
  for (std::size_t k = 0; k < first_order.size(); ++k) map_row(0, i++) = 1.0;
  for (std::size_t r = 0; r < ramp_sigma.size(); ++r, i += 2) map_row(0, i) = 1.0;
  for (std::size_t s = 0; s < oscillators.size(); ++s, i += 2) map_row(0, i) = 1.0;
}

ShapingFilter build_shaping_filter(const NoiseModel& model, const ShapingOptions& options) {
  if (const std::string problem = options.validate(); !problem.empty()) {
    throw ConfigError("noise model shaping options: " + problem);
  }
  ShapingFilter filter;
  for (const NoiseTerm& term : model.terms) {
    if (const auto* q = std::get_if<QuantizationTerm>(&term)) {
      filter.quantization = std::hypot(filter.quantization, q->q);
    } else if (const auto* arw = std::get_if<AngleRandomWalkTerm>(&term)) {
      filter.white_psd += arw->n * arw->n;
    } else if (const auto* rrw = std::get_if<RateRandomWalkTerm>(&term)) {
      filter.bias_walk_psd += rrw->k * rrw->k;
    } else if (const auto* gm = std::get_if<GaussMarkovTerm>(&term)) {
      add_first_order(filter, gm->sigma, gm->tau_c, options);
    } else if (const auto* flicker = std::get_if<BiasInstabilityTerm>(&term)) {
      const FlickerBank bank =
          design_flicker_bank(flicker->b, options.tau0_s, options.flicker_band_max_s,
                              options.flicker_components_per_decade);
      for (std::size_t k = 0; k < bank.tau_c_s.size(); ++k) {
        add_first_order(filter, bank.sigma[k], bank.tau_c_s[k], options);
      }
    } else if (const auto* ramp = std::get_if<RateRampTerm>(&term)) {
      if (ramp->r != 0.0) filter.ramp_sigma.push_back(std::abs(ramp->r));
    } else if (const auto* sinusoid = std::get_if<SinusoidTerm>(&term)) {
      if (sinusoid->amplitude > 0.0) {
        filter.oscillators.push_back({sinusoid->amplitude, sinusoid->frequency_hz});
      }
    } else {
      throw ConfigError(
          fmt::format("build_shaping_filter: a {} term has no stationary shaping filter; give "
                      "the stationary terms only",
                      term_type_name(term_type(term))));
    }
  }
  return filter;
}

}  // namespace stochnav

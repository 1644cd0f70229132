#include "stochnav/scenario/vibration.hpp"

#include <cmath>
#include <numbers>

#include "stochnav/sim/normal_generator.hpp"

namespace stochnav {

SumOfSinusoids::SumOfSinusoids(std::vector<SinusoidComponent> components)
    : components_(std::move(components)) {
  const std::size_t n = components_.size();
  cos_.assign(n, 0.0);
  sin_.assign(n, 0.0);
  step_cos_.assign(n, 1.0);
  step_sin_.assign(n, 0.0);
  for (const auto& c : components_) {
    const double w = c.omega_radps;
    velocity_coef_.push_back(c.amplitude_mps2 / w);
    displacement_coef_.push_back(c.amplitude_mps2 / (w * w));
    integral_coef_.push_back(c.amplitude_mps2 / (w * w * w));
    displacement_offset_ += c.amplitude_mps2 / (w * w) * std::sin(c.phase_rad);
    integral_offset_ += c.amplitude_mps2 / (w * w * w) * std::cos(c.phase_rad);
  }
}

SumOfSinusoids::Value SumOfSinusoids::evaluate(double tau_s) const {
  Value value;
  for (const auto& c : components_) {
    const double angle = c.omega_radps * tau_s + c.phase_rad;
    const double w = c.omega_radps;
    const double cos_angle = std::cos(angle);
    const double sin_angle = std::sin(angle);
    const double sin_phase = std::sin(c.phase_rad);
    value.acceleration_mps2 += c.amplitude_mps2 * sin_angle;
    value.velocity_mps -= c.amplitude_mps2 / w * cos_angle;
    value.displacement_m -= c.amplitude_mps2 / (w * w) * (sin_angle - sin_phase);
    value.displacement_integral_ms += c.amplitude_mps2 / (w * w * w) *
                                          (cos_angle - std::cos(c.phase_rad)) +
                                      c.amplitude_mps2 / (w * w) * sin_phase * tau_s;
  }
  return value;
}

void SumOfSinusoids::anchor(double tau_s) {
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const double angle = components_[k].omega_radps * tau_s + components_[k].phase_rad;
    cos_[k] = std::cos(angle);
    sin_[k] = std::sin(angle);
  }
  last_tau_s_ = tau_s;
  steps_since_anchor_ = 0;
}

SumOfSinusoids::Value SumOfSinusoids::from_phasors(double tau_s) const {
  double acceleration = 0.0;
  double velocity = 0.0;
  double displacement = 0.0;
  double integral = 0.0;
  const std::size_t n = components_.size();
  for (std::size_t k = 0; k < n; ++k) {
    acceleration += components_[k].amplitude_mps2 * sin_[k];
    velocity += velocity_coef_[k] * cos_[k];
    displacement += displacement_coef_[k] * sin_[k];
    integral += integral_coef_[k] * cos_[k];
  }
  Value value;
  value.acceleration_mps2 = acceleration;
  value.velocity_mps = -velocity;
  value.displacement_m = displacement_offset_ - displacement;
  value.displacement_integral_ms = integral - integral_offset_ + displacement_offset_ * tau_s;
  return value;
}

SumOfSinusoids::Value SumOfSinusoids::evaluate_stepping(double tau_s, double step_s) {
  if (components_.size() <= 2) return evaluate(tau_s);
  if (step_s != step_s_) {
    step_s_ = step_s;
    for (std::size_t k = 0; k < components_.size(); ++k) {
      step_cos_[k] = std::cos(components_[k].omega_radps * step_s);
      step_sin_[k] = std::sin(components_[k].omega_radps * step_s);
    }
    last_tau_s_ = -1.0;
  }
  const bool next_grid_point =
      last_tau_s_ >= 0.0 && std::abs(tau_s - (last_tau_s_ + step_s_)) <= 1e-9 * step_s_;
  if (next_grid_point && steps_since_anchor_ < 4096) {
    for (std::size_t k = 0; k < components_.size(); ++k) {
      const double c = cos_[k] * step_cos_[k] - sin_[k] * step_sin_[k];
      const double s = sin_[k] * step_cos_[k] + cos_[k] * step_sin_[k];
      cos_[k] = c;
      sin_[k] = s;
    }
    // The grid point tau0 + j step, not the caller's rounded tau, keeps phasor and time aligned.
    last_tau_s_ = tau_s;
    ++steps_since_anchor_;
  } else {
    anchor(tau_s);
  }
  return from_phasors(tau_s);
}

double SumOfSinusoids::rms_mps2() const {
  double sum = 0.0;
  for (const auto& c : components_) sum += 0.5 * c.amplitude_mps2 * c.amplitude_mps2;
  return std::sqrt(sum);
}

SumOfSinusoids sine_vibration(double frequency_hz, double amplitude_mps2) {
  // A sin(w tau + pi/2) = A cos(w tau): velocity (A/w) sin(w tau) starts at 0.
  return SumOfSinusoids({{amplitude_mps2, 2.0 * std::numbers::pi * frequency_hz,
                          0.5 * std::numbers::pi}});
}

namespace {

double psd_at(const std::vector<std::array<double, 2>>& psd, double frequency_hz) {
  if (psd.size() == 1) return psd[0][1];
  std::size_t i = 1;
  while (i + 1 < psd.size() && psd[i][0] < frequency_hz) ++i;
  const double x0 = std::log(psd[i - 1][0]);
  const double x1 = std::log(psd[i][0]);
  const double y0 = std::log(psd[i - 1][1]);
  const double y1 = std::log(psd[i][1]);
  const double x = std::log(frequency_hz);
  return std::exp(y0 + (y1 - y0) * (x - x0) / (x1 - x0));
}

}  // namespace

SumOfSinusoids random_vibration(const std::vector<std::array<double, 2>>& psd, double rms_mps2,
                                int components, std::uint64_t seed) {
  NormalGenerator random(seed);
  const double log_first = std::log(psd.front()[0]);
  const double log_last = std::log(psd.size() > 1 ? psd.back()[0] : psd.front()[0] * 2.0);
  const double log_width = (log_last - log_first) / components;
  std::vector<SinusoidComponent> parts;
  double power = 0.0;
  for (int k = 0; k < components; ++k) {
    const double lo = std::exp(log_first + k * log_width);
    const double hi = std::exp(log_first + (k + 1) * log_width);
    const double f = std::exp(log_first + (k + random.uniform()) * log_width);
    const double amplitude = std::sqrt(2.0 * psd_at(psd, f) * (hi - lo));
    parts.push_back({amplitude, 2.0 * std::numbers::pi * f,
                     2.0 * std::numbers::pi * random.uniform()});
    power += 0.5 * amplitude * amplitude;
  }
  const double scale = power > 0.0 ? rms_mps2 / std::sqrt(power) : 0.0;
  for (auto& part : parts) part.amplitude_mps2 *= scale;
  return SumOfSinusoids(std::move(parts));
}

nlohmann::json to_json(const SumOfSinusoids& vibration) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& c : vibration.components()) {
    list.push_back({{"frequency_hz", c.omega_radps / (2.0 * std::numbers::pi)},
                    {"amplitude_mps2", c.amplitude_mps2},
                    {"phase_rad", c.phase_rad}});
  }
  return list;
}

}  // namespace stochnav

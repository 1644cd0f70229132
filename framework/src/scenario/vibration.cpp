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
    amplitude_.push_back(c.amplitude_mps2);
    velocity_coef_.push_back(c.amplitude_mps2 / w);
    displacement_coef_.push_back(c.amplitude_mps2 / (w * w));
    integral_coef_.push_back(c.amplitude_mps2 / (w * w * w));
    displacement_offset_ += c.amplitude_mps2 / (w * w) * std::sin(c.phase_rad);
    integral_offset_ += c.amplitude_mps2 / (w * w * w) * std::cos(c.phase_rad);
  }
}

SumOfSinusoids::Value SumOfSinusoids::evaluate(double tau_s) const {
  double acceleration = 0.0;
  double velocity = 0.0;
  double displacement = 0.0;
  double integral = 0.0;
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const double angle = components_[k].omega_radps * tau_s + components_[k].phase_rad;
    const double cos_angle = std::cos(angle);
    const double sin_angle = std::sin(angle);
    acceleration += amplitude_[k] * sin_angle;
    velocity += velocity_coef_[k] * cos_angle;
    displacement += displacement_coef_[k] * sin_angle;
    integral += integral_coef_[k] * cos_angle;
  }
  Value value;
  value.acceleration_mps2 = acceleration;
  value.velocity_mps = -velocity;
  value.displacement_m = displacement_offset_ - displacement;
  value.displacement_integral_ms = integral - integral_offset_ + displacement_offset_ * tau_s;
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
    acceleration += amplitude_[k] * sin_[k];
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
  // Successive t1 - t0 of a uniform grid differ in their last bits: only a real change of the
  // step re-derives the rotations (256 sin/cos for a random vibration).
  if (std::abs(step_s - step_s_) > 1e-9 * step_s) {
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
    // One pass: rotate each phasor by w_k step and accumulate the four sums (four partial sums
    // each, so the loop vectorises without reassociating a single accumulator).
    const std::size_t n = components_.size();
    double* c = cos_.data();
    double* s = sin_.data();
    const double* sc = step_cos_.data();
    const double* ss = step_sin_.data();
    double acceleration[4] = {0, 0, 0, 0};
    double velocity[4] = {0, 0, 0, 0};
    double displacement[4] = {0, 0, 0, 0};
    double integral[4] = {0, 0, 0, 0};
    std::size_t k = 0;
    for (; k + 4 <= n; k += 4) {
      for (std::size_t j = 0; j < 4; ++j) {
        const double cn = c[k + j] * sc[k + j] - s[k + j] * ss[k + j];
        const double sn = s[k + j] * sc[k + j] + c[k + j] * ss[k + j];
        c[k + j] = cn;
        s[k + j] = sn;
        acceleration[j] += amplitude_[k + j] * sn;
        velocity[j] += velocity_coef_[k + j] * cn;
        displacement[j] += displacement_coef_[k + j] * sn;
        integral[j] += integral_coef_[k + j] * cn;
      }
    }
    for (; k < n; ++k) {
      const double cn = c[k] * sc[k] - s[k] * ss[k];
      const double sn = s[k] * sc[k] + c[k] * ss[k];
      c[k] = cn;
      s[k] = sn;
      acceleration[0] += amplitude_[k] * sn;
      velocity[0] += velocity_coef_[k] * cn;
      displacement[0] += displacement_coef_[k] * sn;
      integral[0] += integral_coef_[k] * cn;
    }
    last_tau_s_ = tau_s;
    ++steps_since_anchor_;
    Value value;
    value.acceleration_mps2 =
        (acceleration[0] + acceleration[1]) + (acceleration[2] + acceleration[3]);
    value.velocity_mps = -((velocity[0] + velocity[1]) + (velocity[2] + velocity[3]));
    value.displacement_m = displacement_offset_ - ((displacement[0] + displacement[1]) +
                                                   (displacement[2] + displacement[3]));
    value.displacement_integral_ms = ((integral[0] + integral[1]) + (integral[2] + integral[3])) -
                                     integral_offset_ + displacement_offset_ * tau_s;
    return value;
  }
  anchor(tau_s);
  return from_phasors(tau_s);
}

double SumOfSinusoids::rms_mps2() const {
  double sum = 0.0;
  for (const auto& c : components_) sum += 0.5 * c.amplitude_mps2 * c.amplitude_mps2;
  return std::sqrt(sum);
}

SumOfSinusoids sine_vibration(double frequency_hz, double amplitude_mps2) {
  // A sin(w tau + pi/2) = A cos(w tau): velocity (A/w) sin(w tau) starts at 0.
  return SumOfSinusoids(
      {{amplitude_mps2, 2.0 * std::numbers::pi * frequency_hz, 0.5 * std::numbers::pi}});
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
    parts.push_back(
        {amplitude, 2.0 * std::numbers::pi * f, 2.0 * std::numbers::pi * random.uniform()});
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

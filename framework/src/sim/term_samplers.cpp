#include "term_samplers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <type_traits>
#include <variant>
#include <vector>

#include "stochnav/model/closed_forms.hpp"
#include "stochnav/sim/flicker_bank.hpp"
#include "stochnav/sim/normal_generator.hpp"

namespace stochnav::sim_detail {

TermSampler::~TermSampler() = default;

namespace {

// Angle noise e, variance Q^2; sample k = (e[k+1] - e[k]) / tau0, so phase = e - e[0] and
// AVAR(m tau0) = 3 Q^2 / tau^2 exactly.
class QuantizationSampler final : public TermSampler {
 public:
  QuantizationSampler(double q, double tau0, std::uint64_t seed)
      : scale_(q / tau0), normal_(seed), previous_(normal_()) {}
  void add_to(std::span<double> out, std::uint64_t /*first_index*/) override {
    for (double& y : out) {
      const double next = normal_();
      y += scale_ * (next - previous_);
      previous_ = next;
    }
  }

 private:
  double scale_;
  NormalGenerator normal_;
  double previous_;
};

// White rate noise of PSD N^2: interval means have variance N^2 / tau0.
class WhiteSampler final : public TermSampler {
 public:
  WhiteSampler(double n, double tau0, std::uint64_t seed)
      : scale_(n / std::sqrt(tau0)), normal_(seed) {}
  void add_to(std::span<double> out, std::uint64_t /*first_index*/) override {
    for (double& y : out) y += scale_ * normal_();
  }

 private:
  double scale_;
  NormalGenerator normal_;
};

// Brownian rate w(t) = K W(t). Over one interval, the increment K W(tau0) and the interval mean
// w + K/tau0 integral_0^tau0 W are jointly Gaussian: with g1, g2 independent standard normals,
// W = sqrt(tau0) g1 and integral W = tau0^(3/2) (g1 / 2 + g2 / sqrt(12)).
class RandomWalkSampler final : public TermSampler {
 public:
  RandomWalkSampler(double k, double tau0, std::uint64_t seed)
      : step_(k * std::sqrt(tau0)), normal_(seed) {}
  void add_to(std::span<double> out, std::uint64_t /*first_index*/) override {
    const double inv_sqrt12 = 1.0 / std::sqrt(12.0);
    for (double& y : out) {
      const double g1 = normal_();
      const double g2 = normal_();
      y += rate_ + step_ * (0.5 * g1 + inv_sqrt12 * g2);
      rate_ += step_ * g1;
    }
  }

 private:
  double step_;
  NormalGenerator normal_;
  double rate_ = 0.0;
};

class RampSampler final : public TermSampler {
 public:
  RampSampler(double r, double tau0) : slope_per_sample_(r * tau0) {}
  void add_to(std::span<double> out, std::uint64_t first_index) override {
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i] += slope_per_sample_ * (static_cast<double>(first_index + i) + 0.5);
    }
  }

 private:
  double slope_per_sample_;
};

// A jump of `size` at time_s: each interval mean carries the part of its interval after it.
class BiasStepSampler final : public TermSampler {
 public:
  BiasStepSampler(const BiasStepTerm& term, double tau0) : term_(term), tau0_(tau0) {}
  void add_to(std::span<double> out, std::uint64_t first_index) override {
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double start = static_cast<double>(first_index + i) * tau0_;
      const double after = std::clamp((start + tau0_ - term_.time_s) / tau0_, 0.0, 1.0);
      out[i] += term_.size * after;
    }
  }

 private:
  BiasStepTerm term_;
  double tau0_;
};

// coefficient * aux(t) at the interval's midpoint (the profile is slow against tau0).
class AuxSensitivitySampler final : public TermSampler {
 public:
  AuxSensitivitySampler(const AuxSensitivityTerm& term, double tau0) : term_(term), tau0_(tau0) {}
  void add_to(std::span<double> out, std::uint64_t first_index) override {
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double mid = (static_cast<double>(first_index + i) + 0.5) * tau0_;
      out[i] += term_.coefficient * term_.profile_at(mid);
    }
  }

 private:
  AuxSensitivityTerm term_;
  double tau0_;
};

// Ornstein-Uhlenbeck state x (variance s^2, correlation time T) and its integral I over each
// interval, discretised exactly. With a = exp(-tau0/T):
//   x' = a x + w1,  I = T (1 - a) x + w2,
//   Var w1 = s^2 (1 - a^2), Cov = s^2 T (1 - a)^2, Var w2 = 2 s^2 T^2 g(tau0/T),
// g from closed_form::ou_integral_shape. With g1, g2 independent standard normals,
// w1 = c11 g1 and w2 = c21 g1 + c22 g2 (Cholesky factor). The sample (interval mean) is
// I / tau0 = mean_gain x + mean_noise_correlated g1 + mean_noise_independent g2.
struct GaussMarkovStep {
  GaussMarkovStep(double sigma, double tau_c, double tau0) {
    const double h = tau0 / tau_c;
    const double one_minus_a = -std::expm1(-h);
    const double one_minus_a2 = -std::expm1(-2.0 * h);
    decay = std::exp(-h);
    state_noise = sigma * std::sqrt(one_minus_a2);
    const double covariance = sigma * sigma * tau_c * one_minus_a * one_minus_a;
    const double integral_variance =
        2.0 * sigma * sigma * tau_c * tau_c * closed_form::ou_integral_shape(h);
    const double c21 = state_noise > 0.0 ? covariance / state_noise : 0.0;
    const double c22 = std::sqrt(std::max(0.0, integral_variance - c21 * c21));
    mean_gain = tau_c * one_minus_a / tau0;
    mean_noise_correlated = c21 / tau0;
    mean_noise_independent = c22 / tau0;
  }
  double decay = 0.0;                   // a
  double state_noise = 0.0;             // c11
  double mean_gain = 0.0;               // T (1 - a) / tau0
  double mean_noise_correlated = 0.0;   // c21 / tau0
  double mean_noise_independent = 0.0;  // c22 / tau0
};

class GaussMarkovSampler final : public TermSampler {
 public:
  GaussMarkovSampler(double sigma, double tau_c, double tau0, std::uint64_t seed)
      : step_(sigma, tau_c, tau0), normal_(seed) {
    state_ = sigma * normal_();  // stationary start
  }

  void add_to(std::span<double> out, std::uint64_t /*first_index*/) override {
    for (double& y : out) {
      const double g1 = normal_();
      const double g2 = normal_();
      y += step_.mean_gain * state_ + step_.mean_noise_correlated * g1 +
           step_.mean_noise_independent * g2;
      state_ = step_.decay * state_ + step_.state_noise * g1;
    }
  }

 private:
  GaussMarkovStep step_;
  NormalGenerator normal_;
  double state_ = 0.0;
};

// A bias-instability bank (sim/flicker_bank.hpp). The c22 g2 parts of all components are added
// as one white sequence of variance sum c22^2 / tau0^2, which has the same distribution (the
// parts are white, Gaussian and independent of all else) for one normal draw per sample
// instead of one per component.
//
// The bank's components advance four at a time, sample by sample: each component's state
// recursion is a serial chain, and interleaving four chains keeps the core busy (one component
// at a time over a block is latency-bound, about three times slower). Each component still
// draws from its own stream in sample order, and adds into a sample in component order.
class FlickerSampler final : public TermSampler {
 public:
  FlickerSampler(double b, double tau0, std::uint64_t seed, double band_max_s) : white_(seed) {
    const FlickerBank bank = design_flicker_bank(b, tau0, band_max_s);
    double white_variance = 0.0;
    for (std::size_t k = 0; k < bank.tau_c_s.size(); ++k) {
      const GaussMarkovStep step(bank.sigma[k], bank.tau_c_s[k], tau0);
      normals_.emplace_back(derive_stream_seed(seed, k + 1));
      steps_.push_back(step);
      states_.push_back(bank.sigma[k] * normals_.back()());  // stationary start
      white_variance += step.mean_noise_independent * step.mean_noise_independent;
    }
    white_sigma_ = std::sqrt(white_variance);
  }
  void add_to(std::span<double> out, std::uint64_t /*first_index*/) override {
    for (double& y : out) y += white_sigma_ * white_();
    std::size_t k = 0;
    for (; k + 4 <= steps_.size(); k += 4) advance<4>(out, k);
    for (; k < steps_.size(); ++k) advance<1>(out, k);
  }

 private:
  template <std::size_t kWidth>
  void advance(std::span<double> out, std::size_t first) {
    std::array<double, kWidth> state;
    for (std::size_t j = 0; j < kWidth; ++j) state[j] = states_[first + j];
    const GaussMarkovStep* step = &steps_[first];
    NormalGenerator* normal = &normals_[first];
    for (double& y : out) {
      for (std::size_t j = 0; j < kWidth; ++j) {
        const double g1 = normal[j]();
        y += step[j].mean_gain * state[j] + step[j].mean_noise_correlated * g1;
        state[j] = step[j].decay * state[j] + step[j].state_noise * g1;
      }
    }
    for (std::size_t j = 0; j < kWidth; ++j) states_[first + j] = state[j];
  }

  NormalGenerator white_;
  double white_sigma_ = 0.0;
  std::vector<NormalGenerator> normals_;
  std::vector<GaussMarkovStep> steps_;
  std::vector<double> states_;
};

// Interval mean of A sin(phi + w t): A [cos(phi + w t_k) - cos(phi + w t_k+1)] / (w tau0).
class SinusoidSampler final : public TermSampler {
 public:
  SinusoidSampler(const SinusoidTerm& term, double tau0, std::uint64_t seed) {
    NormalGenerator source(seed);
    phase_ = term.phase_rad ? *term.phase_rad : 2.0 * std::numbers::pi * source.uniform();
    omega_tau0_ = 2.0 * std::numbers::pi * term.frequency_hz * tau0;
    gain_ = term.amplitude / omega_tau0_;
  }
  void add_to(std::span<double> out, std::uint64_t first_index) override {
    double previous = std::cos(phase_ + omega_tau0_ * static_cast<double>(first_index));
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double next =
          std::cos(phase_ + omega_tau0_ * static_cast<double>(first_index + i + 1));
      out[i] += gain_ * (previous - next);
      previous = next;
    }
  }

 private:
  double phase_ = 0.0;
  double omega_tau0_ = 0.0;
  double gain_ = 0.0;
};

}  // namespace

std::unique_ptr<TermSampler> make_term_sampler(const NoiseTerm& term, double tau0_s,
                                               std::uint64_t stream_seed,
                                               double flicker_band_max_s) {
  return std::visit(
      [&](const auto& t) -> std::unique_ptr<TermSampler> {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, QuantizationTerm>) {
          return std::make_unique<QuantizationSampler>(t.q, tau0_s, stream_seed);
        } else if constexpr (std::is_same_v<T, AngleRandomWalkTerm>) {
          return std::make_unique<WhiteSampler>(t.n, tau0_s, stream_seed);
        } else if constexpr (std::is_same_v<T, BiasInstabilityTerm>) {
          return std::make_unique<FlickerSampler>(t.b, tau0_s, stream_seed, flicker_band_max_s);
        } else if constexpr (std::is_same_v<T, RateRandomWalkTerm>) {
          return std::make_unique<RandomWalkSampler>(t.k, tau0_s, stream_seed);
        } else if constexpr (std::is_same_v<T, RateRampTerm>) {
          return std::make_unique<RampSampler>(t.r, tau0_s);
        } else if constexpr (std::is_same_v<T, GaussMarkovTerm>) {
          return std::make_unique<GaussMarkovSampler>(t.sigma, t.tau_c, tau0_s, stream_seed);
        } else if constexpr (std::is_same_v<T, SinusoidTerm>) {
          return std::make_unique<SinusoidSampler>(t, tau0_s, stream_seed);
        } else if constexpr (std::is_same_v<T, BiasStepTerm>) {
          return std::make_unique<BiasStepSampler>(t, tau0_s);
        } else if constexpr (std::is_same_v<T, AuxSensitivityTerm>) {
          return std::make_unique<AuxSensitivitySampler>(t, tau0_s);
        } else {
          return nullptr;
        }
      },
      term);
}

}  // namespace stochnav::sim_detail

#include "stochnav/model/noise_term.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace stochnav {
namespace {

using D = ParameterDimension;
using R = ParameterRange;

constexpr std::array<TermType, 10> kAllTypes{
    TermType::kQuantization,   TermType::kAngleRandomWalk, TermType::kBiasInstability,
    TermType::kRateRandomWalk, TermType::kRateRamp,        TermType::kGaussMarkov,
    TermType::kSinusoid,       TermType::kNonstationary,   TermType::kBiasStep,
    TermType::kAuxSensitivity,
};

constexpr std::array<std::string_view, 10> kNames{
    "quantization", "angle_random_walk", "bias_instability", "rate_random_walk", "rate_ramp",
    "gauss_markov", "sinusoid",          "nonstationary",    "bias_step",        "aux_sensitivity",
};

constexpr std::array<ParameterSpec, 1> kQuantizationSpecs{{{"Q", D::kAngle, R::kNonNegative, false}}};
constexpr std::array<ParameterSpec, 1> kArwSpecs{
    {{"N", D::kAnglePerRootTime, R::kNonNegative, false}}};
constexpr std::array<ParameterSpec, 1> kBiasSpecs{{{"B", D::kRate, R::kNonNegative, false}}};
constexpr std::array<ParameterSpec, 1> kRrwSpecs{
    {{"K", D::kRatePerRootTime, R::kNonNegative, false}}};
constexpr std::array<ParameterSpec, 1> kRampSpecs{{{"R", D::kRatePerTime, R::kAny, false}}};
constexpr std::array<ParameterSpec, 2> kGaussMarkovSpecs{{
    {"sigma", D::kRate, R::kNonNegative, false},
    {"tau_c", D::kTime, R::kPositive, false},
}};
constexpr std::array<ParameterSpec, 3> kSinusoidSpecs{{
    {"amplitude", D::kRate, R::kNonNegative, false},
    {"frequency_hz", D::kFrequency, R::kPositive, false},
    {"phase_rad", D::kPhase, R::kAny, true},
}};
constexpr std::array<ParameterSpec, 2> kBiasStepSpecs{{
    {"time_s", D::kTime, R::kNonNegative, false},
    {"size", D::kRate, R::kAny, false},
}};
constexpr std::array<ParameterSpec, 5> kAuxSpecs{{
    {"coefficient", D::kRate, R::kAny, false},
    {"profile_start", D::kChannel, R::kAny, true},
    {"profile_rise_per_h", D::kChannel, R::kAny, true},
    {"profile_amplitude", D::kChannel, R::kAny, true},
    {"profile_period_s", D::kTime, R::kPositive, true},
}};

[[noreturn]] void bad_index(std::size_t index) {
  throw std::out_of_range("noise term parameter index " + std::to_string(index));
}

}  // namespace

TermType term_type(const NoiseTerm& term) { return kAllTypes.at(term.index()); }

std::string_view term_type_name(TermType type) {
  return kNames.at(static_cast<std::size_t>(type));
}

std::optional<TermType> parse_term_type(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    if (kNames[i] == name) return kAllTypes[i];
  }
  return std::nullopt;
}

std::span<const TermType> all_term_types() { return kAllTypes; }

std::span<const ParameterSpec> parameter_specs(TermType type) {
  switch (type) {
    case TermType::kQuantization:
      return kQuantizationSpecs;
    case TermType::kAngleRandomWalk:
      return kArwSpecs;
    case TermType::kBiasInstability:
      return kBiasSpecs;
    case TermType::kRateRandomWalk:
      return kRrwSpecs;
    case TermType::kRateRamp:
      return kRampSpecs;
    case TermType::kGaussMarkov:
      return kGaussMarkovSpecs;
    case TermType::kSinusoid:
      return kSinusoidSpecs;
    case TermType::kNonstationary:
      return {};
    case TermType::kBiasStep:
      return kBiasStepSpecs;
    case TermType::kAuxSensitivity:
      return kAuxSpecs;
  }
  return {};
}

std::optional<double> parameter_value(const NoiseTerm& term, std::size_t index) {
  return std::visit(
      [index](const auto& t) -> std::optional<double> {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, QuantizationTerm>) {
          if (index == 0) return t.q;
        } else if constexpr (std::is_same_v<T, AngleRandomWalkTerm>) {
          if (index == 0) return t.n;
        } else if constexpr (std::is_same_v<T, BiasInstabilityTerm>) {
          if (index == 0) return t.b;
        } else if constexpr (std::is_same_v<T, RateRandomWalkTerm>) {
          if (index == 0) return t.k;
        } else if constexpr (std::is_same_v<T, RateRampTerm>) {
          if (index == 0) return t.r;
        } else if constexpr (std::is_same_v<T, GaussMarkovTerm>) {
          if (index == 0) return t.sigma;
          if (index == 1) return t.tau_c;
        } else if constexpr (std::is_same_v<T, SinusoidTerm>) {
          if (index == 0) return t.amplitude;
          if (index == 1) return t.frequency_hz;
          if (index == 2) return t.phase_rad;
        } else if constexpr (std::is_same_v<T, BiasStepTerm>) {
          if (index == 0) return t.time_s;
          if (index == 1) return t.size;
        } else if constexpr (std::is_same_v<T, AuxSensitivityTerm>) {
          if (index == 0) return t.coefficient;
          if (index == 1) return t.profile_start;
          if (index == 2) return t.profile_rise_per_h;
          if (index == 3) return t.profile_amplitude;
          if (index == 4) return t.profile_period_s;
        }
        bad_index(index);
      },
      term);
}

void set_parameter_value(NoiseTerm& term, std::size_t index, std::optional<double> value) {
  std::visit(
      [index, value](auto& t) {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, SinusoidTerm>) {
          if (index == 2) {
            t.phase_rad = value;
            return;
          }
        }
        if constexpr (std::is_same_v<T, AuxSensitivityTerm>) {
          if (index >= 1 && index <= 4) {
            std::optional<double>* fields[] = {&t.profile_start, &t.profile_rise_per_h,
                                               &t.profile_amplitude, &t.profile_period_s};
            *fields[index - 1] = value;
            return;
          }
        }
        if (!value) bad_index(index);
        const double v = *value;
        if constexpr (std::is_same_v<T, QuantizationTerm>) {
          if (index == 0) return void(t.q = v);
        } else if constexpr (std::is_same_v<T, AngleRandomWalkTerm>) {
          if (index == 0) return void(t.n = v);
        } else if constexpr (std::is_same_v<T, BiasInstabilityTerm>) {
          if (index == 0) return void(t.b = v);
        } else if constexpr (std::is_same_v<T, RateRandomWalkTerm>) {
          if (index == 0) return void(t.k = v);
        } else if constexpr (std::is_same_v<T, RateRampTerm>) {
          if (index == 0) return void(t.r = v);
        } else if constexpr (std::is_same_v<T, GaussMarkovTerm>) {
          if (index == 0) return void(t.sigma = v);
          if (index == 1) return void(t.tau_c = v);
        } else if constexpr (std::is_same_v<T, SinusoidTerm>) {
          if (index == 0) return void(t.amplitude = v);
          if (index == 1) return void(t.frequency_hz = v);
        } else if constexpr (std::is_same_v<T, BiasStepTerm>) {
          if (index == 0) return void(t.time_s = v);
          if (index == 1) return void(t.size = v);
        } else if constexpr (std::is_same_v<T, AuxSensitivityTerm>) {
          if (index == 0) return void(t.coefficient = v);
        }
        bad_index(index);
      },
      term);
}

NoiseTerm make_term(TermType type) {
  switch (type) {
    case TermType::kQuantization:
      return QuantizationTerm{};
    case TermType::kAngleRandomWalk:
      return AngleRandomWalkTerm{};
    case TermType::kBiasInstability:
      return BiasInstabilityTerm{};
    case TermType::kRateRandomWalk:
      return RateRandomWalkTerm{};
    case TermType::kRateRamp:
      return RateRampTerm{};
    case TermType::kGaussMarkov:
      return GaussMarkovTerm{};
    case TermType::kSinusoid:
      return SinusoidTerm{};
    case TermType::kNonstationary:
      return NonstationaryTerm{};
    case TermType::kBiasStep:
      return BiasStepTerm{};
    case TermType::kAuxSensitivity:
      return AuxSensitivityTerm{};
  }
  return NonstationaryTerm{};
}

bool is_deterministic(TermType type) {
  return type == TermType::kRateRamp || type == TermType::kBiasStep ||
         type == TermType::kAuxSensitivity;
}

double AuxSensitivityTerm::profile_at(double t_s) const {
  const double period = profile_period_s.value_or(1800.0);
  return profile_start.value_or(25.0) + profile_rise_per_h.value_or(10.0) * t_s / 3600.0 +
         profile_amplitude.value_or(2.0) * std::sin(2.0 * std::numbers::pi * t_s / period);
}

}  // namespace stochnav

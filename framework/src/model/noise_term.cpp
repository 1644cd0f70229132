#include "stochnav/model/noise_term.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace stochnav {
namespace {

using D = ParameterDimension;
using R = ParameterRange;

constexpr std::array<TermType, 8> kAllTypes{
    TermType::kQuantization,   TermType::kAngleRandomWalk, TermType::kBiasInstability,
    TermType::kRateRandomWalk, TermType::kRateRamp,        TermType::kGaussMarkov,
    TermType::kSinusoid,       TermType::kNonstationary,
};

constexpr std::array<std::string_view, 8> kNames{
    "quantization",     "angle_random_walk", "bias_instability", "rate_random_walk",
    "rate_ramp",        "gauss_markov",      "sinusoid",         "nonstationary",
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
  }
  return NonstationaryTerm{};
}

}  // namespace stochnav

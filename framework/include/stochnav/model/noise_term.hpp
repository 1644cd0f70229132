#pragma once
// The noise-term vocabulary of DESIGN.md ("Units and vocabulary"), as plain value types.
//
// Every coefficient is held in the natural SI units of the signal it perturbs: for a gyro the
// rate is in rad/s (so Q is in rad, N in rad/sqrt(s), B in rad/s, K in rad/s/sqrt(s), R in
// rad/s^2), for an accelerometer in m/s^2 (Q in m/s, N in m/s/sqrt(s), ...), for plain data in
// the signal's own unit. Conversions to and from the IEEE 952 reporting units used in JSON live
// in one place: model/reporting_units.hpp. Closed-form Allan variances: model/allan_variance.hpp.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace stochnav {

/// The term types, in the order of the NoiseTerm variant alternatives.
enum class TermType {
  kQuantization,
  kAngleRandomWalk,
  kBiasInstability,
  kRateRandomWalk,
  kRateRamp,
  kGaussMarkov,
  kSinusoid,
  kNonstationary,
  kBiasStep,
  kAuxSensitivity,
};

/// Angle (or velocity) quantization. AVAR 3 Q^2 / tau^2.
struct QuantizationTerm {
  double q = 0.0;  ///< Q, signal*s (rad for gyros, m/s for accelerometers), >= 0
};

/// White rate noise. AVAR N^2 / tau.
struct AngleRandomWalkTerm {
  double n = 0.0;  ///< N, signal*sqrt(s) = signal/sqrt(Hz) (rad/sqrt(s) for gyros), >= 0
};

/// Flicker rate noise. AVAR (2 ln 2 / pi) B^2: a flat floor of 0.664 B in deviation.
struct BiasInstabilityTerm {
  double b = 0.0;  ///< B, signal (rad/s for gyros), >= 0
};

/// Random walk of the rate. AVAR K^2 tau / 3.
struct RateRandomWalkTerm {
  double k = 0.0;  ///< K, signal/sqrt(s) (rad/s/sqrt(s) for gyros), >= 0
};

/// Deterministic rate ramp R t. AVAR R^2 tau^2 / 2.
struct RateRampTerm {
  double r = 0.0;  ///< R, signal/s (rad/s^2 for gyros); the sign gives the ramp's direction
};

/// First-order Gauss-Markov (Ornstein-Uhlenbeck) rate noise, stationary standard deviation
/// sigma and correlation time tau_c. AVAR (2 s^2 T/tau)[1 - (T/2tau)(3 - 4e^(-tau/T) + e^(-2tau/T))].
struct GaussMarkovTerm {
  double sigma = 0.0;  ///< stationary standard deviation, signal, >= 0
  double tau_c = 0.0;  ///< correlation time (s), > 0
};

/// Sinusoidal rate A sin(2 pi f t + phase). AVAR A^2 sin^4(pi f tau) / (pi f tau)^2.
struct SinusoidTerm {
  double amplitude = 0.0;     ///< A, signal, >= 0
  double frequency_hz = 0.0;  ///< f (Hz), > 0
  /// Phase at t = 0 (rad). Absent: the simulation draws it uniformly from its seed.
  std::optional<double> phase_rad;
};

/// Over [start_s, end_s) of record time the sum of the model's other terms is multiplied by
/// `scale`.
struct NonstationarySegment {
  double start_s = 0.0;  ///< record time (s), >= 0
  double end_s = 0.0;    ///< record time (s), > start_s
  double scale = 1.0;    ///< factor on the other terms' rate samples, >= 0
};

/// Time-localised scaling of the rest of the model (vibration episodes). It has no Allan-variance
/// contribution in the stationary closed form: it shows in DAVAR, not in AVAR.
struct NonstationaryTerm {
  std::vector<NonstationarySegment> segments;  ///< ascending, non-overlapping, at least one
};

/// Deterministic jump of the bias: `size` is added to every rate sample at record time >=
/// time_s. No stationary Allan-variance contribution: diagnose finds it in the time domain
/// (diagnose/deterministic_effects.hpp).
struct BiasStepTerm {
  double time_s = 0.0;  ///< record time of the jump (s), >= 0
  double size = 0.0;    ///< jump of the rate, signal (rad/s for gyros); any sign
};

/// Bias linear in an auxiliary channel of the record (temperature): the rate carries
/// coefficient * aux(t), aux read from the column `column` of the input file. No stationary
/// Allan-variance contribution: diagnose finds it by regression on the channel.
///
/// For simulation only, the channel's profile (a linear rise plus a slow sinusoid):
///   aux(t) = profile_start + profile_rise_per_h * t / 3600 + profile_amplitude sin(2 pi t /
///   profile_period_s); absent values take the defaults below. `simulate noise` writes aux(t)
///   as the column `column`.
struct AuxSensitivityTerm {
  std::string column = "temperature_c";  ///< CSV column of the auxiliary channel
  double coefficient = 0.0;  ///< signal per unit of the channel (rad/s per degC); any sign
  std::optional<double> profile_start;       ///< channel units; default 25
  std::optional<double> profile_rise_per_h;  ///< channel units per hour; default 10
  std::optional<double> profile_amplitude;   ///< channel units; default 2
  std::optional<double> profile_period_s;    ///< s, > 0; default 1800

  /// The simulated channel value at record time t_s (defaults filled in).
  double profile_at(double t_s) const;
};

using NoiseTerm = std::variant<QuantizationTerm, AngleRandomWalkTerm, BiasInstabilityTerm,
                               RateRandomWalkTerm, RateRampTerm, GaussMarkovTerm, SinusoidTerm,
                               NonstationaryTerm, BiasStepTerm, AuxSensitivityTerm>;

/// True for the deterministic terms diagnose finds in the time domain and removes from the
/// record (rate_ramp, bias_step, aux_sensitivity); the rest is the stochastic model.
bool is_deterministic(TermType type);

/// The type of a term.
TermType term_type(const NoiseTerm& term);

/// The vocabulary name: "quantization", "angle_random_walk", "bias_instability",
/// "rate_random_walk", "rate_ramp", "gauss_markov", "sinusoid", "nonstationary", "bias_step",
/// "aux_sensitivity".
std::string_view term_type_name(TermType type);

/// Inverse of term_type_name; nullopt for an unknown name.
std::optional<TermType> parse_term_type(std::string_view name);

/// All term types in TermType order.
std::span<const TermType> all_term_types();

/// Physical dimension of a scalar parameter, which fixes its reporting unit.
enum class ParameterDimension {
  kAngle,                ///< Q: signal*s
  kAnglePerRootTime,     ///< N: signal*sqrt(s)
  kRate,                 ///< B, Gauss-Markov sigma, sinusoid amplitude: signal
  kRatePerRootTime,      ///< K: signal/sqrt(s)
  kRatePerTime,          ///< R: signal/s
  kTime,                 ///< tau_c: s
  kFrequency,            ///< frequency_hz: Hz
  kPhase,                ///< phase_rad: rad
  kChannel,              ///< aux profile values: the auxiliary channel's own unit (no conversion)
};

/// Which values a scalar parameter may take.
enum class ParameterRange { kNonNegative, kPositive, kAny };

/// A scalar parameter of a term type, as named in JSON.
struct ParameterSpec {
  std::string_view name;  ///< JSON key, e.g. "N", "tau_c"
  ParameterDimension dimension;
  ParameterRange range;
  bool optional;  ///< may be absent (only the sinusoid phase)
};

/// The scalar parameters of a term type, in JSON order. Empty for kNonstationary (segments);
/// the aux_sensitivity column is a string, outside these.
std::span<const ParameterSpec> parameter_specs(TermType type);

/// Value of scalar parameter `index` of parameter_specs(term_type(term)) in natural units;
/// nullopt when an optional parameter is absent.
std::optional<double> parameter_value(const NoiseTerm& term, std::size_t index);

/// Sets scalar parameter `index` (natural units); nullopt clears an optional parameter.
void set_parameter_value(NoiseTerm& term, std::size_t index, std::optional<double> value);

/// A default-constructed term of the given type (all parameters zero, no segments).
NoiseTerm make_term(TermType type);

}  // namespace stochnav

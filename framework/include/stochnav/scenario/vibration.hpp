#pragma once
// Linear vibration as a sum of sinusoids, with closed-form velocity, displacement and the
// integral of the displacement, so IMU increments of a vibrating tool are exact at any output
// rate, however far the vibration lies above the Nyquist frequency.
//
// Random vibration from a PSD table (method): the band [f_first, f_last] of the table is cut into
// `components` bins equally spaced in log f; each bin k holds one sinusoid at a frequency drawn
// uniformly (in log f) inside the bin, with a uniform random phase and amplitude
// A_k = sqrt(2 S(f_k) df_k), S log-log interpolated in the table; all amplitudes are then scaled
// so the RMS of the sum, sqrt(sum A_k^2 / 2), equals the stated RMS exactly. The realisation is a
// stationary Gaussian-like process whose one-sided PSD follows the table's shape.

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

namespace stochnav {

struct SinusoidComponent {
  double amplitude_mps2 = 0.0;  ///< peak acceleration (m/s^2)
  double omega_radps = 0.0;     ///< angular frequency 2 pi f (rad/s), > 0
  double phase_rad = 0.0;       ///< phase at tau = 0 (rad)
};

/// Acceleration a(tau) = sum A_k sin(w_k tau + phi_k), tau = time since the vibration started.
/// Velocity and displacement are the antiderivatives fixed by:
///   velocity(tau)     = -sum (A_k / w_k) cos(w_k tau + phi_k)   (zero mean; jumps at the start
///                        from 0 to velocity(0) unless phi_k make it vanish),
///   displacement(tau) = integral_0^tau velocity                 (continuous, 0 at tau = 0),
///   displacement_integral(tau) = integral_0^tau displacement.
class SumOfSinusoids final {
 public:
  SumOfSinusoids() = default;
  explicit SumOfSinusoids(std::vector<SinusoidComponent> components);

  struct Value {
    double velocity_mps = 0.0;
    double displacement_m = 0.0;
    double displacement_integral_ms = 0.0;  ///< m*s
    double acceleration_mps2 = 0.0;
  };

  /// Direct evaluation (one sin/cos per component).
  Value evaluate(double tau_s) const;

  /// Streaming evaluation on a uniform grid tau = tau0 + j step: cheaper (one complex multiply
  /// per component), re-anchored with evaluate() every 4096 steps so rounding cannot build up.
  /// Falls back to evaluate() when tau is not the next grid point.
  Value evaluate_stepping(double tau_s, double step_s);

  const std::vector<SinusoidComponent>& components() const { return components_; }
  double rms_mps2() const;

 private:
  std::vector<SinusoidComponent> components_;
  // Stepping state: cos/sin of (w_k tau + phi_k) at the last tau, and of w_k step.
  std::vector<double> cos_, sin_, step_cos_, step_sin_;
  // Per component A/w, A/w^2, A/w^3; constants sum (A/w^2) sin phi and sum (A/w^3) cos phi.
  std::vector<double> amplitude_, velocity_coef_, displacement_coef_, integral_coef_;
  double displacement_offset_ = 0.0;
  double integral_offset_ = 0.0;
  double last_tau_s_ = -1.0;
  double step_s_ = 0.0;
  int steps_since_anchor_ = 0;
  Value from_phasors(double tau_s) const;
  void anchor(double tau_s);
};

/// A single sine a(tau) = A cos(w tau), which starts from rest (velocity 0 at tau = 0).
SumOfSinusoids sine_vibration(double frequency_hz, double amplitude_mps2);

/// Random vibration from a PSD table by the method above; `psd` rows (f Hz, S (m/s^2)^2/Hz),
/// f ascending and > 0, S > 0. Deterministic in `seed`.
SumOfSinusoids random_vibration(const std::vector<std::array<double, 2>>& psd, double rms_mps2,
                                int components, std::uint64_t seed);

/// The components as JSON: [{"frequency_hz", "amplitude_mps2", "phase_rad"}, ...].
nlohmann::json to_json(const SumOfSinusoids& vibration);

}  // namespace stochnav

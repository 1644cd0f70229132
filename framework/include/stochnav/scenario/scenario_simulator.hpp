#pragma once
// Streaming IMU simulation of a scenario: exact increments of the true motion plus sensor errors.
//
// Epoch k (k = 1, 2, ..., epoch_count()) covers [(k - 1) / rate, k / rate]. Per axis:
//   measured = (1 + scale_factor) ideal + (constant_bias + turn_on_bias) dt + n_k dt
// where ideal is the exact increment (rad or m/s), and n_k the sample k - 1 of the axis' noise
// (sim/noise_generator.hpp: the mean noise rate over the interval) = noise + scheduled noise. The
// scheduled noise model carries a nonstationary term whose segments are the phases, with the
// phase's noise scale (exactly what scheduled_noise_model() returns and scenario.json echoes),
// so inside a phase its coefficients are multiplied by that scale. The turn-on biases are drawn
// once per run from the seed.
//
// Randomness, all from the one seed (sim/normal_generator.hpp derive_stream_seed): noise of axis
// a (gyro x, y, z = 0..2, accel x, y, z = 3..5) from streams 100 + a (noise) and 200 + a
// (scheduled); turn-on bias from 2000 + a; random vibration of phase p from 3000 + p; aid errors
// from 4000. Memory is independent of the duration (blocks of 4096 samples per noise stream).
// The noise of the six axes is generated a block ahead by background threads
// (sim/block_pipeline.hpp) while the caller integrates the true motion; the records do not
// depend on the number of threads.

#include <array>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "stochnav/ins/strapdown.hpp"
#include "stochnav/scenario/scenario_config.hpp"
#include "stochnav/scenario/true_motion.hpp"
#include "stochnav/sim/block_pipeline.hpp"
#include "stochnav/sim/noise_generator.hpp"

namespace stochnav {

struct ScenarioEpoch {
  ImuIncrement measured;  ///< with sensor errors (rad, m/s)
  ImuIncrement ideal;     ///< exact increments of the true motion (rad, m/s)
  TruthSample truth;      ///< true state at measured.t_s
};

class ScenarioSimulator final {
 public:
  /// `sensor_errors` false gives measured == ideal (noise-free). Throws ConfigError when a noise
  /// model cannot be simulated.
  ScenarioSimulator(const ScenarioConfig& config, std::uint64_t seed, bool sensor_errors = true);
  ~ScenarioSimulator();
  ScenarioSimulator(const ScenarioSimulator&) = delete;
  ScenarioSimulator& operator=(const ScenarioSimulator&) = delete;

  std::uint64_t epoch_count() const { return epoch_count_; }
  /// Epochs produced so far.
  std::uint64_t epochs_done() const { return next_epoch_ - 1; }
  double rate_hz() const { return rate_hz_; }

  /// Produces the next epoch. Precondition: epochs_done() < epoch_count(). With `with_truth`
  /// false, epoch.truth is left untouched (saves a motion evaluation per epoch).
  void next(ScenarioEpoch& epoch, bool with_truth = true);

  /// The true state at t = 0 (the initial condition of a strapdown run).
  TruthSample initial_truth();

  TrueMotion& motion() { return *motion_; }

  /// Turn-on biases drawn for this run: gyro (rad/s) and accelerometer (m/s^2), x y z.
  const std::array<double, 3>& gyro_turn_on_bias() const { return turn_on_bias_[0]; }
  const std::array<double, 3>& accel_turn_on_bias() const { return turn_on_bias_[1]; }

  /// The scheduled-noise model of an axis (0..2 gyro, 3..5 accel) including its nonstationary
  /// term built from the phases (empty terms when the configuration has none).
  const NoiseModel& scheduled_noise_model(std::size_t axis) const { return scheduled_[axis]; }

  /// The noise schedule for scenario.json: per phase, the exact per-axis noise models in force
  /// (noise terms plus scheduled terms times the phase scale, DESIGN.md vocabulary), and the
  /// white-noise variance at the output rate implied by the angle/velocity random walk terms.
  nlohmann::json noise_schedule_json() const;

 private:
  ScenarioConfig config_;
  std::unique_ptr<TrueMotion> motion_;
  double rate_hz_ = 0.0;
  std::uint64_t epoch_count_ = 0;
  std::uint64_t next_epoch_ = 1;
  bool sensor_errors_ = true;
  std::array<NoiseModel, 6> scheduled_;
  // Per axis: the noise and scheduled-noise generators (null without terms), and the axis'
  // stream in the pipeline of summed samples (-1: no noise); all axes are consumed in
  // lockstep. The pipeline calls the generators, so it is declared after them (destroyed first).
  std::array<std::unique_ptr<NoiseGenerator>, 6> noise_;
  std::array<std::unique_ptr<NoiseGenerator>, 6> scheduled_noise_;
  std::array<int, 6> noise_stream_{-1, -1, -1, -1, -1, -1};
  std::unique_ptr<BlockPipeline> noise_blocks_;
  std::size_t block_used_ = 0;
  std::array<std::array<double, 3>, 2> turn_on_bias_{};
  std::array<double, 6> bias_{};  // constant + turn-on, natural units
  std::array<double, 6> scale_factor_{};
};

/// A noise term with every signal-proportional coefficient multiplied by `scale` (times, phases
/// and frequencies unchanged), i.e. the term of `scale` times the process.
NoiseTerm scaled_term(const NoiseTerm& term, double scale);

}  // namespace stochnav

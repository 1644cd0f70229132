#include "stochnav/scenario/scenario_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "stochnav/core/errors.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/sim/normal_generator.hpp"

namespace stochnav {
namespace {

constexpr std::size_t kBlock = 4096;

// The amplitude factor on the scheduled noise in `phase`: the phase's own scale times the
// square roots of the scenario's variance factors that apply to it.
double scheduled_scale(const ScenarioConfig& config, const ScenarioPhase& phase, bool gyro) {
  const double own = gyro ? phase.gyro_noise_scale : phase.accel_noise_scale;
  double variance = gyro ? config.noise_variance_scale.gyro : config.noise_variance_scale.accel;
  if (!phase.stationary) {
    variance *= gyro ? config.moving_noise_variance_scale.gyro
                     : config.moving_noise_variance_scale.accel;
  }
  return own * std::sqrt(variance);
}

bool has_signal_terms(const NoiseModel& model) {
  for (const auto& term : model.terms) {
    if (term_type(term) != TermType::kNonstationary) return true;
  }
  return false;
}

}  // namespace

NoiseTerm scaled_term(const NoiseTerm& term, double scale) {
  NoiseTerm out = term;
  const TermType type = term_type(term);
  const auto specs = parameter_specs(type);
  for (std::size_t j = 0; j < specs.size(); ++j) {
    const ParameterDimension d = specs[j].dimension;
    if (d == ParameterDimension::kTime || d == ParameterDimension::kFrequency ||
        d == ParameterDimension::kPhase || d == ParameterDimension::kChannel ||
        (type == TermType::kBiasStep && j == 0)) {
      continue;
    }
    if (const auto value = parameter_value(term, j)) set_parameter_value(out, j, *value * scale);
  }
  return out;
}

ScenarioSimulator::ScenarioSimulator(const ScenarioConfig& config, std::uint64_t seed,
                                     bool sensor_errors)
    : config_(config),
      motion_(make_true_motion(config, seed)),
      rate_hz_(config.imu.rate_hz),
      sensor_errors_(sensor_errors) {
  epoch_count_ = static_cast<std::uint64_t>(std::llround(motion_->duration_s() * rate_hz_));
  const double duration = motion_->duration_s();
  NonstationaryTerm schedule;
  for (const auto& phase : motion_->phases()) {
    if (phase.end_s > phase.start_s) {
      schedule.segments.push_back({phase.start_s, phase.end_s, 0.0});
    }
  }
  for (std::size_t axis = 0; axis < 6; ++axis) {
    const bool gyro = axis < 3;
    const SensorErrorConfig& sensor = gyro ? config.gyro : config.accel;
    const std::size_t i = axis % 3;
    NoiseModel scheduled = sensor.scheduled_noise[i];
    if (has_signal_terms(scheduled)) {
      NonstationaryTerm term = schedule;
      std::size_t s = 0;
      for (const auto& phase : motion_->phases()) {
        if (phase.end_s > phase.start_s) {
          term.segments[s++].scale = scheduled_scale(config, phase, gyro);
        }
      }
      scheduled.terms.push_back(std::move(term));
    }
    scheduled_[axis] = scheduled;
    if (!sensor_errors_) continue;
    if (has_signal_terms(sensor.noise[i])) {
      noise_[axis] = std::make_unique<NoiseGenerator>(
          sensor.noise[i], rate_hz_, derive_stream_seed(seed, 100 + axis), duration);
    }
    if (has_signal_terms(scheduled)) {
      scheduled_noise_[axis] = std::make_unique<NoiseGenerator>(
          scheduled, rate_hz_, derive_stream_seed(seed, 200 + axis), duration);
    }
    NormalGenerator turn_on(derive_stream_seed(seed, 2000 + axis));
    turn_on_bias_[gyro ? 0 : 1][i] = sensor.turn_on_bias_sigma * turn_on();
    bias_[axis] = sensor.constant_bias[i] + turn_on_bias_[gyro ? 0 : 1][i];
    scale_factor_[axis] = sensor.scale_factor[i];
  }
  std::vector<BlockPipeline::Stream> streams;
  for (std::size_t axis = 0; axis < 6; ++axis) {
    NoiseGenerator* noise = noise_[axis].get();
    NoiseGenerator* scheduled = scheduled_noise_[axis].get();
    if (noise == nullptr && scheduled == nullptr) continue;
    noise_stream_[axis] = static_cast<int>(streams.size());
    streams.push_back([noise, scheduled, scratch = std::vector<double>(kBlock)](
                          std::span<double> out) mutable {
      if (noise != nullptr) {
        noise->generate(out);
      } else {
        std::fill(out.begin(), out.end(), 0.0);
      }
      if (scheduled == nullptr) return;
      scheduled->generate(std::span(scratch).first(out.size()));
      for (std::size_t k = 0; k < out.size(); ++k) out[k] += scratch[k];
    });
  }
  if (!streams.empty()) {
    const unsigned threads = BlockPipeline::default_threads(streams.size());
    noise_blocks_ = std::make_unique<BlockPipeline>(std::move(streams), kBlock, threads);
  }
  block_used_ = kBlock;
}

ScenarioSimulator::~ScenarioSimulator() = default;

TruthSample ScenarioSimulator::initial_truth() { return motion_->truth(0.0); }

void ScenarioSimulator::next(ScenarioEpoch& epoch, bool with_truth) {
  const std::uint64_t k = next_epoch_++;
  const double t0 = static_cast<double>(k - 1) / rate_hz_;
  const double t1 = static_cast<double>(k) / rate_hz_;
  const double dt = t1 - t0;
  epoch.ideal.t_s = t1;
  epoch.ideal.dt_s = dt;
  motion_->integrate(t0, t1, epoch.ideal.delta_theta_b, epoch.ideal.delta_v_b);
  epoch.measured.t_s = t1;
  epoch.measured.dt_s = dt;
  if (sensor_errors_) {
    if (block_used_ == kBlock && noise_blocks_) {
      noise_blocks_->advance();
      block_used_ = 0;
    }
    for (std::size_t axis = 0; axis < 6; ++axis) {
      const double ideal =
          axis < 3 ? epoch.ideal.delta_theta_b[axis] : epoch.ideal.delta_v_b[axis - 3];
      const int stream = noise_stream_[axis];
      const double noise = stream < 0 ? 0.0 : noise_blocks_->current(stream)[block_used_];
      const double measured = (1.0 + scale_factor_[axis]) * ideal + (bias_[axis] + noise) * dt;
      if (axis < 3) {
        epoch.measured.delta_theta_b[axis] = measured;
      } else {
        epoch.measured.delta_v_b[axis - 3] = measured;
      }
    }
    ++block_used_;
  } else {
    epoch.measured.delta_theta_b = epoch.ideal.delta_theta_b;
    epoch.measured.delta_v_b = epoch.ideal.delta_v_b;
  }
  if (with_truth) epoch.truth = motion_->truth(t1);
}

nlohmann::json ScenarioSimulator::noise_schedule_json() const {
  using nlohmann::json;
  const double tau0 = 1.0 / rate_hz_;
  json phases = json::array();
  for (const auto& phase : motion_->phases()) {
    json entry = {{"name", phase.name},
                  {"start_s", phase.start_s},
                  {"end_s", phase.end_s},
                  {"stationary", phase.stationary},
                  {"gyro_noise_scale", scheduled_scale(config_, phase, true)},
                  {"accel_noise_scale", scheduled_scale(config_, phase, false)}};
    for (int sensor = 0; sensor < 2; ++sensor) {
      const bool gyro = sensor == 0;
      const SensorErrorConfig& config = gyro ? config_.gyro : config_.accel;
      const double scale = scheduled_scale(config_, phase, gyro);
      json models = json::array();
      json white_variance = json::array();
      for (std::size_t i = 0; i < 3; ++i) {
        NoiseModel model = config.noise[i];
        model.rate_hz = rate_hz_;
        for (const auto& term : config.scheduled_noise[i].terms) {
          model.terms.push_back(scaled_term(term, scale));
        }
        // White-noise variance of the output-rate samples from the random-walk terms.
        double variance = 0.0;
        for (const auto& term : model.terms) {
          if (const auto* arw = std::get_if<AngleRandomWalkTerm>(&term)) {
            variance += arw->n * arw->n / tau0;
          }
        }
        const double unit = si_per_unit(model.unit);
        white_variance.push_back(variance / (unit * unit));
        models.push_back(to_json(model));
      }
      entry[gyro ? "gyro" : "accel"] = models;
      entry[gyro ? "gyro_white_noise_variance" : "accel_white_noise_variance"] = white_variance;
    }
    phases.push_back(std::move(entry));
  }
  return {{"explanation",
           "per phase, the exact noise model of each axis (x, y, z) in force during [start_s, "
           "end_s): the sensor's noise terms plus its scheduled terms multiplied by the phase "
           "scale; *_white_noise_variance is N^2 / tau0 of the random-walk terms at the output "
           "rate, in the square of each model's units"},
          {"output_rate_hz", rate_hz_},
          {"phases", std::move(phases)}};
}

}  // namespace stochnav

// The streaming aligner an embedder feeds epoch by epoch takes the span `stochnav run` takes,
// refuses what run refuses, and aligns exactly as align_at_rest over that span.

#include <gtest/gtest.h>

#include <random>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/streaming_aligner.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/plugin/plugin_registry.hpp"

namespace stochnav {
namespace {

constexpr double kRateHz = 100.0;

NavState site() {
  NavState state;
  state.latitude_rad = 52.0 * kRadPerDeg;
  state.longitude_rad = 4.0 * kRadPerDeg;
  state.height_m = 10.0;
  return state;
}

// A tool at rest at `site` with inclination 30 deg and azimuth 70 deg, white sensor noise;
// from `turn_from_s` on it turns at 5 deg/s about the body z axis (not static).
std::vector<ImuIncrement> record(double duration_s, double turn_from_s = 1e9) {
  const NavState truth = site();
  const Eigen::Matrix3d c_bn =
      quaternion_from_mwd({.inclination_rad = 30.0 * kRadPerDeg, .toolface_rad = 0.0,
                           .azimuth_rad = 70.0 * kRadPerDeg})
          .toRotationMatrix()
          .transpose();
  const Eigen::Vector3d omega_b = c_bn * earth_rate_n(truth.latitude_rad);
  const Eigen::Vector3d f_b = -(c_bn * gravity_n(truth.latitude_rad, truth.height_m));
  std::mt19937_64 engine(5);
  std::normal_distribution<double> normal;
  const double dt = 1.0 / kRateHz;
  std::vector<ImuIncrement> epochs;
  for (long k = 1; k <= std::lround(duration_s * kRateHz); ++k) {
    ImuIncrement increment;
    increment.t_s = static_cast<double>(k) * dt;
    increment.dt_s = dt;
    const double turn = increment.t_s > turn_from_s ? 5.0 * kRadPerDeg : 0.0;
    for (int i = 0; i < 3; ++i) {
      increment.delta_theta_b(i) = omega_b(i) * dt + 1e-7 * normal(engine);
      increment.delta_v_b(i) = f_b(i) * dt + 1e-5 * normal(engine);
    }
    increment.delta_theta_b.z() += turn * dt;
    epochs.push_back(increment);
  }
  return epochs;
}

plugin::AlignmentConfig alignment(double static_s) {
  plugin::AlignmentConfig config;
  config.static_s = static_s;
  return config;
}

struct WhiteModels {
  plugin::PluginRegistry registry{{plugin::bundled_plugin_dir()}};
  std::shared_ptr<plugin::NoiseModelPlugin> make(plugin::SensorGroup group, double n) const {
    const plugin::NoiseModelContext context{
        .group = group, .imu_rate_hz = kRateHz, .params_pointer = "/noise"};
    return registry.create_noise_model("white", {{"N", n}}, context, "/noise");
  }
};

TEST(StreamingAligner, TakesTheStaticSpanAndAlignsAsAlignAtRest) {
  const std::vector<ImuIncrement> epochs = record(200.0);
  StreamingAligner aligner(alignment(120.0), 0.0);
  std::size_t fed = 0;
  while (!aligner.feed(epochs[fed])) ++fed;
  EXPECT_EQ(fed + 1, 12000u) << "120 s at 100 Hz";
  EXPECT_TRUE(aligner.complete());
  EXPECT_DOUBLE_EQ(aligner.end_time_s(), 120.0);
  EXPECT_DOUBLE_EQ(aligner.collected_s(), 120.0);
  EXPECT_THROW((void)aligner.feed(epochs[fed + 1]), std::logic_error);

  const WhiteModels models;
  const auto gyro = models.make(plugin::SensorGroup::kGyro, 0.01);
  const auto accel = models.make(plugin::SensorGroup::kAccel, 0.01);
  NavState tie_on = site();
  tie_on.t_s = aligner.end_time_s();
  FilterOptions options;
  options.gyro_bias_sigma_radps.setConstant(0.05 * kRadPerDeg / 3600.0);
  const AlignedStart streamed = aligner.align(tie_on, options, *gyro, *accel);
  const AlignedStart direct =
      align_at_rest(std::span(epochs).first(12000), tie_on, alignment(120.0), options, *gyro,
                    *accel);
  EXPECT_EQ(streamed.state.q_nb.coeffs(), direct.state.q_nb.coeffs());
  EXPECT_EQ(streamed.options.initial_gyro_bias_radps, direct.options.initial_gyro_bias_radps);
  EXPECT_EQ(streamed.options.attitude_sigma_rad, direct.options.attitude_sigma_rad);
  // And it is an alignment: azimuth within a few sigma of the truth's 70 deg.
  const MwdAttitude angles = mwd_from_quaternion(streamed.state.q_nb);
  EXPECT_NEAR(angles.azimuth_rad * kDegPerRad, 70.0,
              4.0 * streamed.options.attitude_sigma_rad.z() * kDegPerRad + 0.5);
}

TEST(StreamingAligner, RefusesASpanThatMovesOrEndsEarly) {
  const auto message_of = [](const StreamingAligner& aligner) -> std::string {
    try {
      aligner.check();
    } catch (const ConfigError& error) {
      return error.what();
    }
    return "";
  };
  const std::vector<ImuIncrement> turning = record(130.0, 60.0);
  StreamingAligner moving(alignment(120.0), 0.0);
  for (const ImuIncrement& increment : turning) {
    if (moving.feed(increment)) break;
  }
  const std::string not_static = message_of(moving);
  EXPECT_NE(not_static.find("/initial_state/alignment/static_s"), std::string::npos) << not_static;
  EXPECT_NE(not_static.find("not static"), std::string::npos) << not_static;

  const std::vector<ImuIncrement> short_record = record(50.0);
  StreamingAligner early(alignment(120.0), 0.0);
  for (const ImuIncrement& increment : short_record) EXPECT_FALSE(early.feed(increment));
  EXPECT_FALSE(early.complete());
  const std::string ended = message_of(early);
  EXPECT_NE(ended.find("holds only 50 s"), std::string::npos) << ended;
}

}  // namespace
}  // namespace stochnav

#pragma once
// The GoogleTest fixture of the noise-model property tests (noise_model_properties.hpp), for
// test files that instantiate the suite for their own plugins:
//
//   #include "stochnav/testing/noise_model_case.hpp"
//   using stochnav::testing::NoiseModelCase;
//   using stochnav::testing::NoiseModelProperties;
//   INSTANTIATE_TEST_SUITE_P(
//       MyPlugin, NoiseModelProperties,
//       ::testing::Values(NoiseModelCase{"my_type", {{"sigma", 0.5}}, SensorGroup::kGyro,
//                                        {.times_s = {0.0, 599.5, 600.0}}, {"/my/plugins"}}),
//       stochnav::testing::noise_model_case_name);
//
// The executable must also compile stochnav/testing/noise_model_properties.hpp (the TEST_Ps)
// in exactly one of its source files, and link GTest::gtest and GTest::gtest_main.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "stochnav/plugin/noise_model_checks.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/testing/plugin_test_support.hpp"

namespace stochnav::testing {

/// One model under test: a plugin type with its params, and where and when to check it.
struct NoiseModelCase {
  std::string type;
  nlohmann::json params;
  plugin::SensorGroup group = plugin::SensorGroup::kGyro;
  /// Start times (put a time-varying model's features among times_s), steps, tolerances.
  plugin::PropertyCheckOptions checks = {};
  /// Plugin folders; empty: plugin::default_search_path() ($STOCHNAV_PLUGIN_PATH, then the
  /// plugin folder of the stochnav library in use).
  std::vector<std::filesystem::path> search_path = {};
  double imu_rate_hz = 100.0;  ///< NoiseModelContext::imu_rate_hz
};

/// The factory of the case's plugin on `params`, params under "/noise/<group>/params".
inline std::shared_ptr<plugin::NoiseModelPlugin> make_case_model(const NoiseModelCase& c,
                                                                 const nlohmann::json& params) {
  plugin::NoiseModelContext context;
  context.group = c.group;
  context.imu_rate_hz = c.imu_rate_hz;
  const std::string group(plugin::sensor_group_name(c.group));
  context.params_pointer = "/noise/" + group + "/params";
  return registry_for(c.search_path)
      .create_noise_model(c.type, params, context, "/noise/" + group + "/plugin");
}

inline void PrintTo(const NoiseModelCase& c, std::ostream* os) {
  *os << c.type << " " << plugin::sensor_group_name(c.group) << " " << c.params.dump();
}

/// "<type>_<group>_<index>".
inline std::string noise_model_case_name(const ::testing::TestParamInfo<NoiseModelCase>& info) {
  return info.param.type + "_" + std::string(plugin::sensor_group_name(info.param.group)) + "_" +
         std::to_string(info.index);
}

class NoiseModelProperties : public ::testing::TestWithParam<NoiseModelCase> {
 protected:
  void SetUp() override { model_ = make_case_model(GetParam(), GetParam().params); }

  const plugin::NoiseModelPlugin& model() const { return *model_; }
  const plugin::PropertyCheckOptions& checks() const { return GetParam().checks; }
  plugin::NoiseModelRebuild rebuild() const {
    const NoiseModelCase c = GetParam();
    return [c](const nlohmann::json& params) { return make_case_model(c, params); };
  }

 private:
  std::shared_ptr<plugin::NoiseModelPlugin> model_;
};

}  // namespace stochnav::testing

#pragma once
// The GoogleTest fixture of the aid property tests (aid_properties.hpp), for test files that
// instantiate the suite for their own plugins:
//
//   #include "stochnav/testing/aid_case.hpp"
//   using stochnav::testing::AidCase;
//   using stochnav::testing::AidProperties;
//   AidCase survey_case() {
//     AidCase c{"inclination_survey", {{"sigma_deg", 0.1}}};
//     c.truth = ...;                                  // the true state at c.t_s
//     c.data = stochnav::plugin::AidData("survey", {"t", "inclination_deg"},
//                                        {{1.0}, {60.0}});  // what the tool at c.truth measures
//     c.search_path = {"/my/plugins"};
//     return c;
//   }
//   INSTANTIATE_TEST_SUITE_P(MyPlugin, AidProperties, ::testing::Values(survey_case()),
//                            stochnav::testing::aid_case_name);
//
// The data are the aid's measurements made consistent with the truth by the author of the case
// (plugin/aid_checks.hpp): the suite checks that the residual vanishes there, then perturbs the
// truth by every core error state. The executable must also compile
// stochnav/testing/aid_properties.hpp (the TEST_Ps) in exactly one of its source files, and link
// GTest::gtest and GTest::gtest_main.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "stochnav/ins/nav_state.hpp"
#include "stochnav/plugin/aid_checks.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/testing/plugin_test_support.hpp"

namespace stochnav::testing {

/// One aid under test: a plugin type with its params, the aid data and the true state that
/// agree, and when to check it.
struct AidCase {
  std::string type;
  nlohmann::json params;
  plugin::AidData data = {};  ///< what the tool at `truth` measures (aid data columns)
  NavState truth = {};        ///< the true state at t_s
  double t_s = 1.0;           ///< a time (s) at which the aid has a measurement
  /// Interval aids (AidPlugin::measures_interval_mean): T (s) since the aid's previous
  /// measurement epoch; 0 for the others. The IMU sample is steady_imu_sample(truth, t_s, T).
  double interval_s = 0.0;
  double start_s = 0.0;  ///< the run's start: AidContext::initial_state is the truth at start_s
  plugin::AidCheckOptions checks = {};  ///< steps and tolerances
  /// Plugin folders; empty: plugin::default_search_path().
  std::vector<std::filesystem::path> search_path = {};
};

/// The case's epoch for the checks.
inline plugin::AidCheckCase aid_check_case(const AidCase& c) {
  return {c.truth, c.t_s, plugin::steady_imu_sample(c.truth, c.t_s, c.interval_s)};
}

/// The factory of the case's plugin on `params`, params under "/aids/0/params". `c` (its data)
/// must outlive the aid.
inline std::shared_ptr<plugin::AidPlugin> make_case_aid(const AidCase& c,
                                                        const nlohmann::json& params) {
  plugin::AidContext context;
  context.params_pointer = "/aids/0/params";
  context.data = &c.data;
  context.initial_state = c.truth;
  context.initial_state.t_s = c.start_s;
  return registry_for(c.search_path).create_aid(c.type, params, context, "/aids/0/plugin");
}

inline void PrintTo(const AidCase& c, std::ostream* os) {
  *os << c.type << " " << c.params.dump() << " at t = " << c.t_s << " s";
}

/// "<type>_<index>".
inline std::string aid_case_name(const ::testing::TestParamInfo<AidCase>& info) {
  return info.param.type + "_" + std::to_string(info.index);
}

class AidProperties : public ::testing::TestWithParam<AidCase> {
 protected:
  void SetUp() override { aid_ = make_case_aid(GetParam(), GetParam().params); }

  const plugin::AidPlugin& aid() const { return *aid_; }
  plugin::AidCheckCase epoch() const { return aid_check_case(GetParam()); }
  const plugin::AidCheckOptions& checks() const { return GetParam().checks; }
  const nlohmann::json& params() const { return GetParam().params; }
  /// Builds with the case's data: GetParam() lives as long as the test.
  plugin::AidRebuild rebuild() const {
    const AidCase* c = &GetParam();
    return [c](const nlohmann::json& params) { return make_case_aid(*c, params); };
  }

 private:
  std::shared_ptr<plugin::AidPlugin> aid_;
};

}  // namespace stochnav::testing

// The plugin loader: discovery, the real reason of every load failure, object lifetime, and the
// `stochnav plugins` command.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_cli.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "temp_dir.hpp"

namespace stochnav::plugin {
namespace {

namespace fs = std::filesystem;

fs::path fixture(const std::string& folder, const std::string& name) {
  return fs::path(STOCHNAV_TEST_FIXTURE_DIR) / folder / ("stochnav_test_" + name + ".so");
}

std::string load_error(const fs::path& file) {
  try {
    check_plugin_file(file);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(loaded)";
}

TEST(PluginLoader, BundledFolderIsBesideTheLibraryAndHoldsTheInTreePlugins) {
  EXPECT_EQ(fs::weakly_canonical(bundled_plugin_dir()),
            fs::weakly_canonical(STOCHNAV_BUILD_PLUGIN_DIR));
  const PluginRegistry registry({bundled_plugin_dir()});
  EXPECT_TRUE(registry.problems().empty());
  const auto& white = registry.find(PluginKind::kNoiseModel, "white", "/p");
  EXPECT_EQ(white.api_version, kPluginApiVersion);
  EXPECT_TRUE(white.can_fit);
  EXPECT_EQ(registry.find(PluginKind::kNoiseModel, "gauss_markov", "/p").kind,
            PluginKind::kNoiseModel);
}

TEST(PluginLoader, SearchPathOrderIsConfigFolderEnvironmentThenBundled) {
  ::setenv("STOCHNAV_PLUGIN_PATH", "/tmp/a::/tmp/b", 1);
  const auto path = default_search_path("/cfg");
  ::unsetenv("STOCHNAV_PLUGIN_PATH");
  ASSERT_EQ(path.size(), 4u);
  EXPECT_EQ(path[0], fs::path("/cfg"));
  EXPECT_EQ(path[1], fs::path("/tmp/a"));
  EXPECT_EQ(path[2], fs::path("/tmp/b"));
  EXPECT_EQ(path[3], bundled_plugin_dir());
}

TEST(PluginLoader, MissingFileSaysNotFound) {
  EXPECT_NE(load_error("/nonexistent/stochnav_x.so").find("plugin library not found"),
            std::string::npos);
}

TEST(PluginLoader, WrongApiVersionIsRefused) {
  const std::string message = load_error(fixture("wrong_api", "wrong_api"));
  EXPECT_NE(message.find("plugin API version 999"), std::string::npos) << message;
  EXPECT_NE(message.find("needs version " + std::to_string(kPluginApiVersion)), std::string::npos);
}

TEST(PluginLoader, UnresolvedSymbolNamesTheSymbol) {
  const std::string message = load_error(fixture("unresolved", "unresolved"));
  EXPECT_NE(message.find("undefined symbol"), std::string::npos) << message;
  EXPECT_NE(message.find("stochnav_test_symbol_nobody_defines"), std::string::npos) << message;
  EXPECT_EQ(message.find("Bad file descriptor"), std::string::npos) << message;
}

TEST(PluginLoader, LibraryWithoutInfoIsNotAPlugin) {
  const std::string message = load_error(fixture("not_a_plugin", "not_a_plugin"));
  EXPECT_NE(message.find("not a stochnav plugin"), std::string::npos) << message;
}

TEST(PluginLoader, FactoryExceptionBecomesConfigErrorWithItsMessage) {
  const PluginRegistry registry({fixture("factory_throws", "factory_throws").parent_path()});
  NoiseModelContext context;
  context.params_pointer = "/noise/gyro/params";
  try {
    registry.create_noise_model("factory_throws", {}, context, "/noise/gyro/plugin");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("/noise/gyro/params"), std::string::npos) << message;
    EXPECT_NE(message.find("factory exploded on purpose"), std::string::npos) << message;
  }
}

TEST(PluginLoader, DuplicateTypeIsReportedAndRefused) {
  const PluginRegistry registry({fixture("duplicate", "duplicate_a").parent_path()});
  ASSERT_EQ(registry.problems().size(), 1u);
  EXPECT_NE(registry.problems()[0].reason.find("duplicate noise plugin type 'duplicate'"),
            std::string::npos);
  try {
    registry.find(PluginKind::kNoiseModel, "duplicate", "/noise/gyro/plugin");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("provided by two libraries"), std::string::npos);
  }
}

TEST(PluginLoader, UnknownTypeListsKnownOnes) {
  const PluginRegistry registry({bundled_plugin_dir()});
  try {
    registry.create_noise_model("whte", {}, {}, "/noise/gyro/plugin");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("/noise/gyro/plugin: unknown noise plugin type 'whte'"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("white"), std::string::npos);
  }
}

TEST(PluginLoader, ObjectsOutliveTheRegistry) {
  std::shared_ptr<NoiseModelPlugin> model;
  {
    const PluginRegistry registry({bundled_plugin_dir()});
    NoiseModelContext context;
    model = registry.create_noise_model("white", {{"N", 0.1}}, context, "/p");
  }
  Eigen::MatrixXd q(3, 3);
  model->white_noise_covariance(0.0, 1.0, q);
  EXPECT_GT(q(0, 0), 0.0);
  EXPECT_EQ(model->type(), "white");
}

TEST(PluginsCommand, ListShowsTheBundledPlugins) {
  testing::TempDir scratch;
  const auto result = testing::run_cli("plugins list", scratch.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("noise  white"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("noise  gauss_markov"), std::string::npos) << result.out;
}

TEST(PluginsCommand, CheckGivesExitCode2AndTheReason) {
  testing::TempDir scratch;
  struct Case {
    fs::path file;
    std::string reason;
  };
  const Case cases[] = {
      {"/nonexistent/stochnav_x.so", "not found"},
      {fixture("wrong_api", "wrong_api"), "plugin API version 999"},
      {fixture("unresolved", "unresolved"),
       "undefined symbol: stochnav_test_symbol_nobody_defines"},
      {fixture("not_a_plugin", "not_a_plugin"), "not a stochnav plugin"},
  };
  for (const auto& c : cases) {
    const auto result =
        testing::run_cli("plugins check '" + c.file.string() + "'", scratch.path().string());
    EXPECT_EQ(result.exit_code, 2) << c.file;
    EXPECT_NE(result.err.find(c.reason), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  }
  const auto good = testing::run_cli(
      "plugins check '" + (bundled_plugin_dir() / "stochnav_noise_white.so").string() + "'",
      scratch.path().string());
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_NE(good.out.find("white"), std::string::npos);
}

TEST(PluginsCommand, ListWithADuplicateFails) {
  testing::TempDir scratch;
  const auto result = testing::run_cli(
      "plugins list --path '" + fixture("duplicate", "duplicate_a").parent_path().string() + "'",
      scratch.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("duplicate noise plugin type"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace stochnav::plugin

namespace stochnav::plugin {
namespace {

TEST(AidPlugins, AreBuiltWithTheRunsAidDataAndGate) {
  const PluginRegistry registry({fs::path(STOCHNAV_TEST_FIXTURE_DIR) / "aid"});
  ASSERT_TRUE(registry.problems().empty());
  EXPECT_EQ(registry.find(PluginKind::kAid, "test_zupt", "/aids/0/plugin").kind, PluginKind::kAid);
  const AidData data("aids.csv", {"t", "zupt"}, {{0.0, 1.0, 2.0}, {1.0, 0.0, 1.0}});
  NavState initial;
  const AidContext context{"/aids/0/params", &data, initial, {}};
  const auto aid =
      registry.create_aid("test_zupt", {{"sigma_m_s", 0.02}}, context, "/aids/0/plugin");
  EXPECT_TRUE(aid->has_measurement(0.0));
  EXPECT_FALSE(aid->has_measurement(1.0));
  EXPECT_FALSE(aid->has_measurement(0.5));
  NavState state;
  state.v_n = Eigen::Vector3d(0.1, -0.2, 0.3);
  Eigen::VectorXd z(3);
  Eigen::MatrixXd h(3, core_state::kSize), r(3, 3);
  ASSERT_TRUE(aid->measure(2.0, state, ImuSample{}, z, h, r));
  EXPECT_EQ(z, state.v_n);
  EXPECT_EQ(h(1, core_state::kVelocity + 1), 1.0);
  EXPECT_NEAR(r(2, 2), 4e-4, 1e-15);
  EXPECT_NEAR(aid->gate().threshold, 16.266, 1e-3);  // chi2(3) at 99.9 %
  try {
    registry.create_aid("test_zupt", {{"column", "stuck"}}, context, "/aids/0/plugin");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what())
                  .find("/aids/0/params/column: aid data aids.csv has no "
                        "column 'stuck'"),
              std::string::npos)
        << error.what();
  }
  EXPECT_THROW(registry.create_noise_model("test_zupt", {}, {}, "/noise/gyro/plugin"), ConfigError);
}

}  // namespace
}  // namespace stochnav::plugin

namespace stochnav::plugin {
namespace {

TEST(PluginsCommand, ShowFindsPluginsInTheConfigFolderAndReportsFactoryErrors) {
  testing::TempDir scratch;
  fs::copy_file(fixture("factory_throws", "factory_throws"),
                scratch.path() / "stochnav_test_factory_throws.so");
  scratch.write("imu.csv", "t,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n0,0,0,0,0,0,0\n");
  scratch.write("good.json", R"({"data": {"imu": "imu.csv"},
    "noise": {"gyro": {"plugin": "gauss_markov", "params": {"sigma": 1, "tau_c": 10}},
              "accel": {"plugin": "white", "params": {"N": 0.02}}}})");
  scratch.write("throws.json", R"({"data": {"imu": "imu.csv"},
    "noise": {"gyro": {"plugin": "factory_throws"},
              "accel": {"plugin": "white", "params": {"N": 0.02}}}})");
  scratch.write("bad_param.json", R"({"data": {"imu": "imu.csv"},
    "noise": {"gyro": {"plugin": "white", "params": {"N": -1}},
              "accel": {"plugin": "white", "params": {"N": 0.02}}}})");
  const auto good =
      testing::run_cli("plugins show '" + scratch.file("good.json") + "'", scratch.path().string());
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_NE(good.out.find("error state: 18 states"), std::string::npos) << good.out;
  const auto throws = testing::run_cli("plugins show '" + scratch.file("throws.json") + "'",
                                       scratch.path().string());
  EXPECT_EQ(throws.exit_code, 2);
  EXPECT_NE(throws.err.find("/noise/gyro/params: plugin 'factory_throws'"), std::string::npos)
      << throws.err;
  EXPECT_NE(throws.err.find("factory exploded on purpose"), std::string::npos) << throws.err;
  const auto bad = testing::run_cli("plugins show '" + scratch.file("bad_param.json") + "'",
                                    scratch.path().string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("/noise/gyro/params/N: found -1; expected a number >= 0 (deg/sqrt(h))"),
            std::string::npos)
      << bad.err;
}

TEST(PluginsCommand, ShowPrintsTheNavigatorsLayoutAndTakesARecordingFolder) {
  testing::TempDir scratch;
  fs::create_directories(scratch.path() / "recording");
  scratch.write("recording/imu.csv",
                "t,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n0,0,0,0,0,0,0\n");
  // No "data" section: --data gives the recording, as for run.
  scratch.write("scaled.json", R"({
    "noise": {"gyro": {"plugin": "gauss_markov", "params": {"sigma": 1, "tau_c": 10}},
              "accel": {"plugin": "white", "params": {"N": 0.02}}},
    "filter": {"scale_factor_sigma_ppm": {"gyro": 100, "accel": 0}}})");
  const auto shown = testing::run_cli("plugins show '" + scratch.file("scaled.json") +
                                          "' --data '" + scratch.file("recording") + "'",
                                      scratch.path().string());
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  // 15 core + 3 gyro scale factors + 3 Gauss-Markov states: what MwdNavigator lays out.
  EXPECT_NE(shown.out.find("error state: 21 states"), std::string::npos) << shown.out;
  EXPECT_NE(shown.out.find("gyro_scale_factor"), std::string::npos) << shown.out;
  EXPECT_EQ(shown.out.find("accel_scale_factor"), std::string::npos) << shown.out;
  const auto without_data =
      testing::run_cli("plugins show '" + scratch.file("scaled.json") + "'",
                       scratch.path().string());
  EXPECT_EQ(without_data.exit_code, 2);
  EXPECT_NE(without_data.err.find("/data"), std::string::npos) << without_data.err;
}

}  // namespace
}  // namespace stochnav::plugin

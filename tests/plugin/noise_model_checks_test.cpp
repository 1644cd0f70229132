// The property checks of plugin/noise_model_checks.hpp find broken models, in process and through
// `stochnav plugins check LIB --params JSON` (exit code 2, one line naming the first failure;
// each failure a line of the report on standard output).

#include "stochnav/plugin/noise_model_checks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "run_cli.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "temp_dir.hpp"

namespace stochnav::plugin {
namespace {

namespace fs = std::filesystem;

const fs::path kBroken = fs::path(STOCHNAV_TEST_FIXTURE_DIR) / "broken_properties" /
                         "stochnav_test_broken_properties.so";

NoiseModelContext gyro_context() {
  NoiseModelContext context;
  context.group = SensorGroup::kGyro;
  context.params_pointer = "/params";
  return context;
}

std::vector<std::string> failures_of(const PluginRegistry& registry, std::string_view type,
                                     const nlohmann::json& params) {
  const auto build = [&](const nlohmann::json& p) {
    return registry.create_noise_model(type, p, gyro_context(), "/plugin");
  };
  return check_noise_model(*build(params), build);
}

bool any_contains(const std::vector<std::string>& lines, std::string_view text) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& line) { return line.find(text) != std::string::npos; });
}

TEST(NoiseModelChecks, FindTheBrokenPropertiesAndPassAGoodModel) {
  const PluginRegistry broken = PluginRegistry::of_file(kBroken);
  const auto failures = failures_of(broken, "broken_properties", {{"N", 0.1}});
  EXPECT_TRUE(any_contains(failures, "composition at t = 3 s of 0.37 s and 1.9 s: Qw"));
  EXPECT_TRUE(any_contains(failures, "round trip: the model rebuilt from params()"));
  EXPECT_FALSE(any_contains(failures, "zero step"));
  EXPECT_FALSE(any_contains(failures, "not positive semi-definite"));

  const PluginRegistry bundled({bundled_plugin_dir()});
  EXPECT_TRUE(failures_of(bundled, "white", {{"N", 0.05}}).empty());
  EXPECT_THROW(PluginRegistry::of_file("/nonexistent/stochnav_x.so"), ConfigError);
}

TEST(PluginsCommand, CheckWithParamsRunsThePropertiesAndReportsEachFailure) {
  stochnav::testing::TempDir scratch;
  const auto broken = stochnav::testing::run_cli(
      "plugins check '" + kBroken.string() + "' --params '{\"N\": 0.1}' --times 1,2",
      scratch.path().string());
  EXPECT_EQ(broken.exit_code, 2) << broken.err;
  // Composition of Qw at both times, and the round trip (twice: equal neither way): each a
  // line of the report on standard output, one line on stderr naming the first and the count.
  EXPECT_EQ(std::count(broken.err.begin(), broken.err.end(), '\n'), 1) << broken.err;
  EXPECT_NE(broken.err.find("4 property checks failed, the first: composition at t = 1 s"),
            std::string::npos)
      << broken.err;
  EXPECT_NE(broken.out.find("failed: composition at t = 2 s"), std::string::npos) << broken.out;
  std::size_t listed = 0;
  for (std::size_t at = broken.out.find("\nfailed: "); at != std::string::npos;
       at = broken.out.find("\nfailed: ", at + 1)) {
    ++listed;
  }
  EXPECT_EQ(listed, 4u) << broken.out;

  const fs::path gauss_markov = bundled_plugin_dir() / "stochnav_noise_gauss_markov.so";
  const auto good =
      stochnav::testing::run_cli("plugins check '" + gauss_markov.string() +
                                     "' --params '{\"sigma\": 0.5, \"tau_c\": 30}' --group accel",
                                 scratch.path().string());
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_NE(good.out.find("gauss_markov (accel): sigma = 0.5 m/s/h"), std::string::npos)
      << good.out;

  const auto typo = stochnav::testing::run_cli(
      "plugins check '" + gauss_markov.string() + "' --params '{\"sigam\": 0.5, \"tau_c\": 30}'",
      scratch.path().string());
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("--params/sigam: unknown key 'sigam'; did you mean 'sigma'?"),
            std::string::npos)
      << typo.err;
}

}  // namespace
}  // namespace stochnav::plugin

// The aid checks of plugin/aid_checks.hpp pass every bundled aid and find each broken property
// of a deliberately broken aid (a sign flip or a wrong column in H, a residual not zero at the
// truth, R not positive definite, an entry not written), in process and through
// `stochnav plugins check LIB --params JSON` (exit code 2, one line naming the first failure;
// each failure a line of the report on standard output).

#include "stochnav/plugin/aid_checks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "bundled_aid_cases.hpp"
#include "run_cli.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "temp_dir.hpp"

namespace stochnav::plugin {
namespace {

namespace fs = std::filesystem;
using stochnav::testing::AidCase;

const fs::path kBrokenAid =
    fs::path(STOCHNAV_TEST_FIXTURE_DIR) / "broken_aid" / "stochnav_test_broken_aid.so";

std::vector<std::string> failures_of(const AidCase& c) {
  const auto build = [&](const nlohmann::json& params) {
    return stochnav::testing::make_case_aid(c, params);
  };
  return check_aid(*build(c.params), build, c.params, stochnav::testing::aid_check_case(c),
                   c.checks);
}

bool any_contains(const std::vector<std::string>& lines, std::string_view text) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& line) { return line.find(text) != std::string::npos; });
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  return text;
}

TEST(AidChecks, PassEveryBundledAid) {
  for (const AidCase& c : bundled_aid_cases::all()) {
    const auto failures = failures_of(c);
    EXPECT_TRUE(failures.empty()) << c.type << " " << c.params.dump() << "\n" << joined(failures);
  }
}

// The broken aid at rest, with a row at t = 1 s.
AidCase broken(const std::string& fault) {
  AidCase c{"broken_aid", {{"fault", fault}}};
  c.truth = bundled_aid_cases::inclined_tool(0.0);
  c.data = AidData("aids.csv", {"t"}, {{0.0, 1.0}});
  c.search_path = {kBrokenAid.parent_path()};
  return c;
}

TEST(AidChecks, PassTheBrokenAidWithoutAFault) {
  EXPECT_TRUE(failures_of(broken("none")).empty()) << joined(failures_of(broken("none")));
}

TEST(AidChecks, FindASignFlipInH) {
  const auto failures = failures_of(broken("sign"));
  ASSERT_EQ(failures.size(), 3u) << joined(failures);  // one per velocity column
  EXPECT_EQ(failures[0],
            "jacobian: H(0, 3) (dv_east) = -1, finite difference 1 (difference -2 > 0.000101)");
}

TEST(AidChecks, FindAWrongColumnInH) {
  const auto failures = failures_of(broken("column"));
  // H on the position columns where the derivative is zero, none on the velocity columns.
  EXPECT_EQ(failures.size(), 6u) << joined(failures);
  EXPECT_TRUE(any_contains(failures, "jacobian: H(0, 0) (dr_east) = 1, finite difference 0"));
  EXPECT_TRUE(any_contains(failures, "jacobian: H(2, 5) (dv_up) = 0, finite difference 1"));
}

TEST(AidChecks, FindAResidualThatIsNotZeroAtTheTruth) {
  const auto failures = failures_of(broken("offset"));
  ASSERT_EQ(failures.size(), 1u) << joined(failures);
  EXPECT_EQ(failures[0].rfind("truth: z(0) = 0.01 at the true state, 10 sigma", 0), 0u)
      << failures[0];
}

TEST(AidChecks, FindACovarianceThatIsNotPositiveDefinite) {
  const auto failures = failures_of(broken("covariance"));
  EXPECT_TRUE(any_contains(failures,
                           "covariance: R not positive definite (smallest eigenvalue "
                           "-1e-06"))
      << joined(failures);
}

TEST(AidChecks, FindAnEntryMeasureDidNotWrite) {
  const auto failures = failures_of(broken("unwritten"));
  EXPECT_TRUE(any_contains(failures, "sizes: H(2, 14) (b_g_z) not written or not finite (nan)"))
      << joined(failures);
}

TEST(AidChecks, ReportATimeWithoutAMeasurement) {
  AidCase c = broken("none");
  c.t_s = 0.5;
  const auto failures = failures_of(c);
  ASSERT_EQ(failures.size(), 1u) << joined(failures);
  EXPECT_EQ(failures[0].rfind("sizes: has_measurement(0.5 s) is false", 0), 0u) << failures[0];
}

TEST(AidChecks, RejectUnusableOptions) {
  AidCase c = broken("none");
  c.checks.step = 0.0;
  EXPECT_EQ(failures_of(c), std::vector<std::string>{"options: step <= 0"});
}

// --- the CLI ---

fs::path write_csv(const fs::path& folder, const std::string& name, const std::string& text) {
  std::ofstream(folder / name) << text;
  return folder / name;
}

TEST(PluginsCommand, CheckWithParamsRunsTheAidChecks) {
  stochnav::testing::TempDir scratch;
  const fs::path zupt = bundled_plugin_dir() / "stochnav_aid_zupt.so";
  const fs::path flags = write_csv(scratch.path(), "zupt.csv", "t,zupt\n0,1\n1,1\n");
  const auto good = stochnav::testing::run_cli("plugins check '" + zupt.string() +
                                                   "' --params '{\"sigma_velocity_mps\": 0.002}' " +
                                                   "--aid-data '" + flags.string() + "'",
                                               scratch.path().string());
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_NE(good.out.find("aid: zupt: source = flags"), std::string::npos) << good.out;
  EXPECT_NE(good.out.find("properties: sizes, covariance, residual at the truth, jacobian, "
                          "params round trip hold at t = 1 s"),
            std::string::npos)
      << good.out;

  // Moving at 1 m/s east: the zero-velocity data no longer agree with the state.
  const auto moving = stochnav::testing::run_cli(
      "plugins check '" + zupt.string() + "' --params '{}' --aid-data '" + flags.string() +
          "' --state '{\"v_n_mps\": [1, 0, 0]}'",
      scratch.path().string());
  EXPECT_EQ(moving.exit_code, 2) << moving.err;
  EXPECT_NE(moving.err.find("(aid at t = 1 s): truth: z(0) = 1 at the true state"),
            std::string::npos)
      << moving.err;

  // Drilling at 20 m/h: the rig's rate agrees with the state moving along its axis.
  const fs::path rop = bundled_plugin_dir() / "stochnav_aid_rop.so";
  const fs::path rates = write_csv(scratch.path(), "rop.csv", "t,rop_mph\n0,20\n1,20\n");
  const auto drilling = stochnav::testing::run_cli(
      "plugins check '" + rop.string() + "' --params '{}' --aid-data '" + rates.string() +
          "' --state '{\"axial_speed_mps\": 0.0055555555555555558}' --interval 1",
      scratch.path().string());
  EXPECT_EQ(drilling.exit_code, 0) << drilling.err;
  const auto without_data = stochnav::testing::run_cli(
      "plugins check '" + rop.string() + "' --params '{}'", scratch.path().string());
  EXPECT_EQ(without_data.exit_code, 2);
  EXPECT_NE(without_data.err.find("--params: aid data (none given) has no column 'rop_mph'"),
            std::string::npos)
      << without_data.err;

  const fs::path rows = write_csv(scratch.path(), "rows.csv", "t\n0\n1\n");
  const auto sign = stochnav::testing::run_cli(
      "plugins check '" + kBrokenAid.string() + "' --params '{\"fault\": \"sign\"}' --aid-data '" +
          rows.string() + "'",
      scratch.path().string());
  EXPECT_EQ(sign.exit_code, 2) << sign.err;
  EXPECT_EQ(std::count(sign.err.begin(), sign.err.end(), '\n'), 1) << sign.err;
  EXPECT_NE(sign.err.find("3 property checks failed"), std::string::npos) << sign.err;
  EXPECT_NE(sign.out.find("failed: jacobian: H(2, 5) (dv_up) = -1, finite difference 1"),
            std::string::npos)
      << sign.out;

  const auto typo = stochnav::testing::run_cli(
      "plugins check '" + zupt.string() + "' --params '{\"sigma_velocity\": 0.1}' --aid-data '" +
          flags.string() + "'",
      scratch.path().string());
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("--params/sigma_velocity: unknown key 'sigma_velocity'"),
            std::string::npos)
      << typo.err;

  const auto bad_state = stochnav::testing::run_cli(
      "plugins check '" + zupt.string() + "' --params '{}' --aid-data '" + flags.string() +
          "' --state '{\"latitude\": 30}'",
      scratch.path().string());
  EXPECT_EQ(bad_state.exit_code, 2);
  EXPECT_NE(bad_state.err.find("--state/latitude: unknown key; expected only axial_speed_mps"),
            std::string::npos)
      << bad_state.err;
}

}  // namespace
}  // namespace stochnav::plugin

// A navigation run's result written by a shard reads back bit for bit, NaN, infinities and
// negative zero included, also inside its JSON members; a damaged file is a clear InputError.

#include "stochnav/experiment/run_result_json.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

bool same_bits(double a, double b) {
  // NaN payloads are not kept, only NaN-ness.
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

NavigationRunResult awkward_run() {
  NavigationRunResult run;
  run.has_truth = true;
  ErrorStatistics statistics;
  statistics.add({0.1, -1.0 / 3.0, 2e-308, kNaN, 123456.789012345678, -0.0, 1e300, 7.0, 1.0});
  statistics.add({0.2 + 0.1, 5e-324, 1.0, kNaN, 1.0 / 7.0, 3.0, -2.5, 0.0, 0.30000000000000004});
  run.statistics = statistics;
  run.health.singular_innovations = 3;
  run.health.non_finite = 1;
  run.epochs = 15000;
  run.duration_s = 150.0;
  run.wall_seconds = 0.123456789;
  run.error_series.push_back(
      {0.01, {1, 2, 3, kNaN, -kInf, 6, 7, 8, 9}, {0.1, 0.2, 0.3, kNaN, kInf, 0.6, 0.7, 0.8, -0.0}});
  run.noise_models = {{"gyro", "white N 0.05"}, {"accel", nullptr}};
  run.fitted = {{"gyro", {{"N", 1.0 / 3.0}, {"B", kNaN}}}, {"accel", {{"N", 0.029}}}};
  run.fit_quality = nullptr;
  run.consistency = {{"nees_mean", kNaN},
                     {"nees_samples", 1500.0},
                     {"inside_3sigma", {{"lat_err_m", 0.97}, {"toolface_err_deg", kNaN}}}};
  run.aids = nlohmann::json::array({{{"type", "zupt"}, {"dof", 3}, {"nis_mean", -kInf}}});
  run.consistency_line = "consistency: ok";
  run.self_check = {{"source", "truth"}, {"optimistic", false}, {"reason", ""}};
  run.warnings = {"aid zupt rejected 12 %"};
  run.survey_stations = 4;
  return run;
}

// Through text, as a job file carries it.
NavigationRunResult round_trip(const NavigationRunResult& run, bool with_series) {
  const std::string text = run_result_to_json(run, with_series).dump();
  return run_result_from_json(nlohmann::json::parse(text), "job_0.json");
}

TEST(RunResultJson, ReadsBackBitForBit) {
  const NavigationRunResult run = awkward_run();
  const NavigationRunResult back = round_trip(run, true);
  EXPECT_EQ(back.has_truth, run.has_truth);
  for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
    SCOPED_TRACE(m);
    EXPECT_TRUE(same_bits(back.statistics.max_abs(m), run.statistics.max_abs(m)));
    EXPECT_TRUE(same_bits(back.statistics.sum_squares(m), run.statistics.sum_squares(m)));
    EXPECT_TRUE(same_bits(back.statistics.rms(m), run.statistics.rms(m)));
    EXPECT_EQ(back.statistics.count(m), run.statistics.count(m));
  }
  EXPECT_EQ(back.health.singular_innovations, 3u);
  EXPECT_EQ(back.health.non_finite, 1u);
  EXPECT_FALSE(back.health.ok());
  EXPECT_EQ(back.epochs, run.epochs);
  EXPECT_TRUE(same_bits(back.wall_seconds, run.wall_seconds));
  ASSERT_EQ(back.error_series.size(), 1u);
  for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
    EXPECT_TRUE(same_bits(back.error_series[0].errors[m], run.error_series[0].errors[m]));
    EXPECT_TRUE(same_bits(back.error_series[0].sigma[m], run.error_series[0].sigma[m]));
  }
  EXPECT_TRUE(std::signbit(back.error_series[0].sigma[8]));  // -0.0 stays negative
  EXPECT_EQ(back.noise_models, run.noise_models);
  EXPECT_TRUE(std::isnan(back.fitted["gyro"]["B"].get<double>()));
  EXPECT_TRUE(same_bits(back.fitted["gyro"]["N"].get<double>(), 1.0 / 3.0));
  EXPECT_TRUE(back.fit_quality.is_null());
  EXPECT_TRUE(std::isnan(back.consistency["nees_mean"].get<double>()));
  EXPECT_TRUE(back.consistency["nees_samples"].is_number_float());
  EXPECT_EQ(back.aids[0]["nis_mean"].get<double>(), -kInf);
  EXPECT_EQ(back.aids[0]["dof"].get<int>(), 3);
  EXPECT_EQ(back.consistency_line, run.consistency_line);
  EXPECT_EQ(back.self_check, run.self_check);
  EXPECT_EQ(back.warnings, run.warnings);
  EXPECT_EQ(back.survey_stations, 4u);
  // Read back, the run writes the same text again.
  EXPECT_EQ(run_result_to_json(back, true).dump(), run_result_to_json(run, true).dump());
}

TEST(RunResultJson, ErrorSeriesOnlyWhenAskedFor) {
  EXPECT_TRUE(round_trip(awkward_run(), false).error_series.empty());
}

TEST(RunResultJson, DamagedJsonIsAnInputErrorNamingTheFile) {
  nlohmann::json json = run_result_to_json(awkward_run(), false);
  json.erase("statistics");
  try {
    run_result_from_json(json, "shards/shard-0-of-2/job_4.json");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what())
                  .find("shards/shard-0-of-2/job_4.json: missing "
                        "\"statistics\""),
              std::string::npos)
        << error.what();
  }
  json = run_result_to_json(awkward_run(), false);
  json["epochs"] = "many";
  EXPECT_THROW(run_result_from_json(json, "job_4.json"), InputError);
}

TEST(NonFiniteMarks, OnlyNonFiniteFloatsAreMarked) {
  const nlohmann::json value = {{"a", kNaN}, {"b", {1, 2.5, kInf}}, {"c", "nan"}, {"d", 3}};
  const nlohmann::json marked = with_non_finite_marked(value);
  EXPECT_EQ(marked["a"], (nlohmann::json{{"non_finite", "nan"}}));
  EXPECT_EQ(marked["b"][2], (nlohmann::json{{"non_finite", "inf"}}));
  EXPECT_EQ(marked["c"], "nan");
  EXPECT_EQ(marked["d"], 3);
  const nlohmann::json back = with_non_finite_restored(nlohmann::json::parse(marked.dump()));
  EXPECT_TRUE(std::isnan(back["a"].get<double>()));
  EXPECT_EQ(back["b"][2].get<double>(), kInf);
  EXPECT_EQ(back["b"][1].get<double>(), 2.5);
}

}  // namespace
}  // namespace stochnav

// The drilling filter off the well it was tuned on, from a field start (tie-on + 600-s static
// alignment in the hole, configs/runs/drilling_recording.json), survey stations checked against
// the truth kept aside (docs/drilling-envelope.md):
//   - sliding (no rotation) on the shipped well for 12 h: every station inside 3 sigma in
//     inclination, azimuth, north, east and TVD. Before, the filter linearised about the INS
//     velocity and the measured specific force (filter/mwd_navigator.hpp: the reference
//     trajectory), read the INS's own velocity error and the accelerometer noise as heading
//     information, claimed a 1.8-deg azimuth and was 10-66 deg off; and the white + rate
//     random walk gyro model let it chase the noise into the bias (the recording config now
//     carries the sensors' flicker terms);
//   - a deliberately wrong gyro model (a bias 25 times too well known) on a sliding well and in
//     an east-west hole: the survey QC without truth flags the run (self_check optimistic).
//   - rotary drilling in a horizontal east-west hole at 60 N from a field start (a heading
//     uncertain by 6 deg after the alignment): every station inside 3 sigma. Before, the
//     first-order attitude error read an unmodelled tilt drift (1/2 psi^2 times the horizontal
//     Earth rate) as heading information and ended 4-6 sigma off in azimuth and north
//     (filter/second_order_attitude.hpp); the test also runs that ablation and sees it fail.
//   - rotary drilling at 160 rpm in an east-west hole at 57 N, three seeds: inside at every epoch
//     (the epoch's mean attitude, not the chord of its ends; ins/strapdown.hpp).
//   - rotary drilling in a horizontal east-west hole at 80 N from a field start: the bank over
//     the heading, its hypotheses' headings consider states there, keeps every station inside
//     on seeds 1 and 3; one filter (seed 1) and hypotheses that update their heading (seed 3)
//     do not; the shipped well at 80 N keeps its first-order heading information.
// Not checked here: sliding east-west at high latitude with heading errors of tens of degrees
// (74 N: inside since the bank decides its consider rule for all its hypotheses alike, at 3.0
// sigma in north at worst). Its evidence is the 8-h family of docs/drilling-envelope.md,
// section 3, a quarter of an hour per well; the rule itself is HeadingHypotheses'
// TheBankHoldsEveryHypothesisHeadingAlike.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "csv_columns.hpp"
#include "json_file.hpp"
#include "run_cli.hpp"
#include "sanitized_build.hpp"
#include "temp_dir.hpp"

namespace {

using stochnav::testing::CsvColumns;
using stochnav::testing::read_csv_columns;
using stochnav::testing::read_json;

// Simulates `scenario` into a folder named by `tag` (once per tag), and runs the shipped
// recording config, edited, from the record's first truth row as tie-on, into a folder named by
// `tag` and `variant`. Returns the run folder.
std::string simulate_and_run(
    const stochnav::testing::TempDir& scratch, const std::string& tag,
    const nlohmann::json& scenario,
    const std::function<void(nlohmann::json&)>& edit_config = [](nlohmann::json&) {},
    const std::string& variant = "") {
  std::ofstream(scratch.file(tag + ".json")) << scenario.dump();
  const std::string data = scratch.file(tag);
  if (!std::filesystem::exists(data)) {
    const auto simulated = stochnav::testing::run_cli(
        "simulate scenario '" + scratch.file(tag + ".json") + "' --out '" + data + "'",
        scratch.path().string());
    EXPECT_EQ(simulated.exit_code, 0) << simulated.err;
  }

  const std::string source = STOCHNAV_SOURCE_DIR;
  const auto truth = read_csv_columns(data + "/truth.csv");
  nlohmann::json config = read_json(source + "/configs/runs/drilling_recording.json");
  config.erase("data");
  config["initial_state"]["tie_on"] = {{"latitude_deg", truth.at("lat").front()},
                                       {"longitude_deg", truth.at("lon").front()},
                                       {"height_m", truth.at("h").front()}};
  edit_config(config);
  const std::string run = tag + "_run" + variant;
  std::ofstream(scratch.file(run + ".json")) << config.dump();
  const std::string out = scratch.file(run);
  const auto result =
      stochnav::testing::run_cli("run '" + scratch.file(run + ".json") + "' --out '" + out +
                                     "' --data '" + data + "' --no-plot",
                                 scratch.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return out;
}

// The shipped scenario with `drilling` and `site` merged into it, simulated and run as above.
std::string simulate_and_run_from_field_start(
    const stochnav::testing::TempDir& scratch, const std::string& tag,
    const nlohmann::json& drilling, const nlohmann::json& site,
    const std::function<void(nlohmann::json&)>& edit_config = [](nlohmann::json&) {},
    std::optional<int> seed = std::nullopt, const std::string& variant = "") {
  const std::string source = STOCHNAV_SOURCE_DIR;
  nlohmann::json scenario = read_json(source + "/configs/scenarios/drilling_build_hold.json");
  scenario["drilling"].merge_patch(drilling);
  nlohmann::json episodes = nlohmann::json::array();  // those inside the shortened record
  for (const auto& episode : scenario["drilling"]["vibration_episodes"]) {
    if (episode["end_s"].get<double>() < scenario["drilling"]["duration_s"].get<double>()) {
      episodes.push_back(episode);
    }
  }
  scenario["drilling"]["vibration_episodes"] = episodes;
  scenario["site"].merge_patch(site);
  if (seed) scenario["seed"] = *seed;
  return simulate_and_run(scratch, tag, scenario, edit_config, variant);
}

// Stations with a finite error and sigma, and how many are inside 3 sigma.
struct StationsInside {
  int counted = 0;
  int inside = 0;
};

StationsInside stations_inside(const stochnav::testing::CsvColumns& errors,
                               const std::string& column, const std::string& sigma_column) {
  StationsInside result;
  for (std::size_t i = 0; i < errors.at(column).size(); ++i) {
    const double error = errors.at(column)[i];
    const double sigma = errors.at(sigma_column)[i];
    if (!std::isfinite(error) || !std::isfinite(sigma)) continue;
    ++result.counted;
    result.inside += std::abs(error) <= 3.0 * sigma ? 1 : 0;
  }
  return result;
}

const double kDuration_s = 43200.0;  // 12 h; the tests that use it skip in sanitized builds
// Long enough for stations in the build (sliding) or several connections (east-west).
const double kWrongModelDuration_s = stochnav::testing::study_size(14400.0, 5400.0);

// Every station quantity of a run inside its own 3 sigma.
void expect_every_station_inside(const std::string& out) {
  const auto errors = read_csv_columns(out + "/survey_errors.csv");
  for (const auto& [column, sigma] : std::vector<std::pair<std::string, std::string>>{
           {"inclination_deg", "inclination_sigma_deg"},
           {"azimuth_deg", "azimuth_sigma_deg"},
           {"north_m", "north_sigma_m"},
           {"east_m", "east_sigma_m"},
           {"tvd_m", "tvd_sigma_m"}}) {
    const StationsInside share = stations_inside(errors, column, sigma);
    EXPECT_EQ(share.inside, share.counted) << column;
  }
}

// Over seeds, not one lucky realisation (the seeds of docs/drilling-envelope.md, section 3).
TEST(DrillingEnvelope, SlidingIsInsideItsThreeSigmaFromAFieldStart) {
  if (!stochnav::testing::study_at_full_size()) {
    GTEST_SKIP() << "12-h runs; the survey-QC tests below run the same navigator under the "
                    "sanitizers";
  }
  const stochnav::testing::TempDir scratch;
  for (const int seed : {7, 2, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::string out = simulate_and_run_from_field_start(
        scratch, "slide_" + std::to_string(seed),
        {{"rotation_rpm", 0}, {"duration_s", kDuration_s}}, nlohmann::json::object(),
        [](nlohmann::json&) {}, seed);
    const auto errors = read_csv_columns(out + "/survey_errors.csv");
    const StationsInside azimuth = stations_inside(errors, "azimuth_deg", "azimuth_sigma_deg");
    EXPECT_GE(azimuth.counted, 8);
    expect_every_station_inside(out);
    // The azimuth no aid observes is honestly uncertain: degrees, not the 1.8 deg claimed before.
    if (azimuth.counted > 0) {
      EXPECT_GT(errors.at("azimuth_sigma_deg").back(), 2.0);
    }
  }
}

// Rotary drilling, horizontal due east at 60 N: the along-hole gyro bias and the heading are
// one unknown there to first order, and the alignment leaves the heading 6 deg uncertain.
std::string east_west_rotary_run(const stochnav::testing::TempDir& scratch, int seed,
                                 const nlohmann::json& filter, const std::string& variant) {
  return simulate_and_run_from_field_start(
      scratch, "east_" + std::to_string(seed),
      {{"well", {{"azimuth_deg", 90}, {"kickoff_md_m", 100}}},
       {"start_md_m", 1000},
       {"duration_s", kDuration_s}},
      {{"latitude_deg", 60}},
      [&](nlohmann::json& config) { config["filter"].merge_patch(filter); }, seed, variant);
}

TEST(DrillingEnvelope, EastWestRotaryIsInsideItsThreeSigmaFromAFieldStart) {
  if (!stochnav::testing::study_at_full_size()) {
    GTEST_SKIP() << "12-h runs; the sliding test covers these code paths under the sanitizers";
  }
  const stochnav::testing::TempDir scratch;
  for (const int seed : {3, 7}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_every_station_inside(
        east_west_rotary_run(scratch, seed, nlohmann::json::object(), "shipped"));
  }
}

// The epochs after the alignment at which an errors.csv column is outside 3 sigma, and the
// worst error in sigmas.
std::pair<int, double> epochs_outside(const CsvColumns& errors, const std::string& column) {
  const auto& t = errors.at("t");
  const auto& error = errors.at(column);
  const auto& sigma = errors.at(column + "_sigma");
  int outside = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] <= 600.0 || !(sigma[i] > 0.0)) continue;  // the alignment
    worst = std::max(worst, std::abs(error[i]) / sigma[i]);
    outside += std::abs(error[i]) > 3.0 * sigma[i] ? 1 : 0;
  }
  return {outside, worst};
}

// Rotary drilling at 160 rpm in an east-west hole at 57 N (examples/drilling_envelope/
// rotary_east_west_57n.json, shortened to 2.5 h; three seeds): north, east, azimuth and
// inclination inside 3 sigma at every epoch after the alignment. Before, the navigator took the
// chord of an epoch's start and end attitudes for its mean, short by theta^2 / 8 across the spin
// axis (0.35 % at 160 rpm and 100 Hz), and rotated the body's velocity increment with it; its
// covariance then lost the cross-hole growth of an uncertain heading, and north ended 3.5-51
// sigma off on 12 of 12 seeds of 6 h (docs/drilling-envelope.md, section 7). The start reaches
// the east-west mirror, so the run is a bank over the heading; with the weights' full
// likelihood (the ablation) seed 2's bank put 0.96 of its weight on the mirror for a while, and
// azimuth and north left their 3 sigma (4.5 and 4.4 sigma).
TEST(DrillingEnvelope, FastRotaryEastWestIsInsideItsThreeSigma) {
  if (!stochnav::testing::study_at_full_size()) {
    GTEST_SKIP() << "2.5-h runs; the unit tests cover the epoch's mean attitude";
  }
  const stochnav::testing::TempDir scratch;
  nlohmann::json scenario = read_json(std::string(STOCHNAV_SOURCE_DIR) +
                                      "/examples/drilling_envelope/rotary_east_west_57n.json");
  scenario["drilling"]["duration_s"] = 9000.0;
  for (const int seed : {1, 2, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    scenario["seed"] = seed;
    const std::string out = simulate_and_run(scratch, "fast_rotary_" + std::to_string(seed),
                                             scenario);
    const auto errors = read_csv_columns(out + "/errors.csv");
    for (const std::string column :
         {"lat_err_m", "lon_err_m", "azimuth_err_deg", "inclination_err_deg"}) {
      const auto [outside, worst] = epochs_outside(errors, column);
      EXPECT_EQ(outside, 0) << column << ": worst " << worst << " sigma";
    }
  }
  scenario["seed"] = 2;
  const auto full_likelihood = read_csv_columns(
      simulate_and_run(
          scratch, "fast_rotary_2", scenario,
          [](nlohmann::json& config) {
            config["filter"]["heading_hypothesis_likelihood_power"] = 1.0;
          },
          "_full_likelihood") +
      "/errors.csv");
  EXPECT_GT(epochs_outside(full_likelihood, "azimuth_err_deg").first, 0)
      << "the full likelihood, seed 2";
}

// The last epoch's error in sigmas.
double end_error_sigmas(const stochnav::testing::CsvColumns& errors, const std::string& column) {
  return std::abs(errors.at(column).back()) / errors.at(column + "_sigma").back();
}

// A start narrower than one hypothesis (heading sigma 3.5 deg against 4) whose heading is 7 deg
// across the east-west line from the truth (2 sigma), on the 160-rpm well at 57 N (seed 2,
// 2.5 h): the start reaches the mirror, so at its first rotation (the scenario's static start
// over) it is split into a bank of hypotheses about 3.5 / 1.5 deg wide. Its
// azimuth and north end inside 3 sigma, and where the weights cannot tell the truth from its
// mirror it says so (heading unresolved). One filter (the ablation, "heading_hypothesis_sigma_
// deg": 0, what such a start was before) settles near the mirror, 5.5 deg off at a sigma of
// 0.6, north 3.5 m off against 0.4, and its self-check has no word for it
// (docs/drilling-envelope.md, section 7).
TEST(DrillingEnvelope, AStartAcrossTheEastWestMirrorIsABankEvenWhenNarrow) {
  if (!stochnav::testing::study_at_full_size()) {
    GTEST_SKIP() << "2.5-h runs; the sanitizers run HeadingHypotheses in filter_tests";
  }
  const stochnav::testing::TempDir scratch;
  nlohmann::json scenario = read_json(std::string(STOCHNAV_SOURCE_DIR) +
                                      "/examples/drilling_envelope/rotary_east_west_57n.json");
  scenario["drilling"]["duration_s"] = 9000.0;
  scenario["seed"] = 2;
  const auto start_across_the_line = [](double hypothesis_sigma_deg) {
    return [hypothesis_sigma_deg](nlohmann::json& config) {
      config.erase("initial_state");  // the truth's first row, with the error below
      config["filter"]["initial_sigma"]["attitude_deg"] = {0.05, 0.05, 3.5};
      config["filter"]["heading_hypothesis_sigma_deg"] = hypothesis_sigma_deg;
      config["initial_error"] = {{"attitude_deg", {0.0, 0.0, 7.0}}};
    };
  };
  const std::string bank_out =
      simulate_and_run(scratch, "mirror_start", scenario, start_across_the_line(4.0), "_bank");
  const std::string one_out =
      simulate_and_run(scratch, "mirror_start", scenario, start_across_the_line(0.0), "_one");
  const nlohmann::json bank = read_json(bank_out + "/metrics.json");
  EXPECT_EQ(bank["heading_hypotheses"]["initial"].get<int>(), 1);
  EXPECT_EQ(bank["heading_hypotheses"]["splits"].get<int>(), 1);
  const auto bank_errors = read_csv_columns(bank_out + "/errors.csv");
  for (const std::string column : {"azimuth_err_deg", "lat_err_m"}) {
    EXPECT_LE(end_error_sigmas(bank_errors, column), 3.0) << column;
    const auto [outside, worst] = epochs_outside(bank_errors, column);
    if (outside > 0) {
      EXPECT_FALSE(bank["self_check"]["heading"]["resolved"].get<bool>())
          << column << " outside 3 sigma at " << outside << " epochs (worst " << worst
          << " sigma) while the heading is called resolved";
    }
  }
  const auto one_errors = read_csv_columns(one_out + "/errors.csv");
  EXPECT_GT(end_error_sigmas(one_errors, "azimuth_err_deg"), 5.0);
  EXPECT_GT(end_error_sigmas(one_errors, "lat_err_m"), 5.0);
  EXPECT_FALSE(read_json(one_out + "/metrics.json")["self_check"].contains("heading"));
}

// The ablation: one first-order filter on the same well is outside on azimuth and north. (The
// start reaches the east-west mirror, so the shipped run is a bank over the heading, which the
// ablation turns off too: it isolates the second-order term; docs/drilling-envelope.md,
// section 7.)
TEST(DrillingEnvelope, EastWestRotaryFirstOrderOnlyLeavesItsThreeSigma) {
  if (!stochnav::testing::study_at_full_size()) {
    GTEST_SKIP() << "the 12-h ablation runs in the release suite only";
  }
  const stochnav::testing::TempDir scratch;
  const auto errors =
      read_csv_columns(east_west_rotary_run(scratch, 3,
                                            {{"second_order_attitude_correlation_s", 0.0},
                                             {"heading_hypothesis_sigma_deg", 0.0}},
                                            "first_order") +
                       "/survey_errors.csv");
  const StationsInside azimuth = stations_inside(errors, "azimuth_deg", "azimuth_sigma_deg");
  const StationsInside north = stations_inside(errors, "north_m", "north_sigma_m");
  EXPECT_LT(azimuth.inside, azimuth.counted);
  EXPECT_LT(north.inside, north.counted);
}

// Rotary drilling, horizontal due east at 80 N, from a field start: the horizontal Earth rate
// is a sixth of the equator's, as large as the gyro's turn-on bias, and the static alignment's
// heading is far from Gaussian (docs/drilling-envelope.md, section 4). The shipped bank over
// the heading (filter/heading_hypotheses.hpp: 4-deg cells, each hypothesis' heading a consider
// state in an east-west hole) keeps every station inside on seeds 1 and 3. The ablations, each
// on the seed where it failed: one filter (no bank) on seed 1, 9-10 sigma off in azimuth and
// north from the first station on; hypotheses that update their heading
// ("heading_hypothesis_consider": false) on seed 3, 2.2 deg off with a sigma of 0.8 at the end,
// but only without the vibration in the model (fix 7; with it, every station inside).
// And the shipped well at 80 N (a vertical start, seed 1), where the rotating cross axes give
// first-order heading information: every station inside and the azimuth known to a fraction of
// a degree (a consider heading there too gave 6.5 deg and north 5 sigma off). 12-h records:
// the first hours simulated alone are a different realisation.
std::string east_west_rotary_80n_run(const stochnav::testing::TempDir& scratch, int seed,
                                     const nlohmann::json& filter = nlohmann::json::object(),
                                     const std::string& variant = "") {
  return simulate_and_run_from_field_start(
      scratch, "east_80n_" + std::to_string(seed),
      {{"well", {{"azimuth_deg", 90}, {"kickoff_md_m", 100}}},
       {"start_md_m", 1000},
       {"duration_s", kDuration_s}},
      {{"latitude_deg", 80}},
      [&](nlohmann::json& config) { config["filter"].merge_patch(filter); }, seed, variant);
}

// Whether some station's azimuth and some station's north position leave their 3 sigma.
bool azimuth_and_north_leave_three_sigma(const std::string& out) {
  const auto errors = read_csv_columns(out + "/survey_errors.csv");
  const StationsInside azimuth = stations_inside(errors, "azimuth_deg", "azimuth_sigma_deg");
  const StationsInside north = stations_inside(errors, "north_m", "north_sigma_m");
  return azimuth.inside < azimuth.counted && north.inside < north.counted;
}

TEST(DrillingEnvelope, EastWestRotaryAt80NTheHeadingBankKeepsItInside) {
  if (!stochnav::testing::study_at_full_size()) {
    GTEST_SKIP() << "12-h runs of a bank of up to 45 navigators; MwdNavigator, ErrorStateFilter "
                    "and HeadingHypotheses run the same code under the sanitizers";
  }
  const stochnav::testing::TempDir scratch;
  for (const int seed : {1, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::string out = east_west_rotary_80n_run(scratch, seed);
    const nlohmann::json hypotheses = read_json(out + "/metrics.json")["heading_hypotheses"];
    EXPECT_GT(hypotheses["initial"].get<int>(), 1) << hypotheses.dump();
    EXPECT_GE(stations_inside(read_csv_columns(out + "/survey_errors.csv"), "azimuth_deg",
                              "azimuth_sigma_deg")
                  .counted,
              8);
    expect_every_station_inside(out);
    const nlohmann::json heading = read_json(out + "/metrics.json")["self_check"]["heading"];
    EXPECT_TRUE(heading["resolved"].get<bool>()) << heading.dump();
  }

  SCOPED_TRACE("the shipped well (a vertical start)");
  const std::string vertical = simulate_and_run_from_field_start(
      scratch, "vertical_80n", {{"duration_s", kDuration_s}}, {{"latitude_deg", 80}},
      [](nlohmann::json&) {}, 1);
  expect_every_station_inside(vertical);
  const auto vertical_errors = read_csv_columns(vertical + "/survey_errors.csv");
  EXPECT_LT(vertical_errors.at("azimuth_sigma_deg").back(), 1.0);
}

// The ablations of the test above, each on the seed where it failed (a test of their own, so
// that the two run side by side within CTest's time limit).
TEST(DrillingEnvelope, EastWestRotaryAt80NItsAblationsLeaveTheirThreeSigma) {
  if (!stochnav::testing::study_at_full_size()) {
    GTEST_SKIP() << "12-h runs of a bank of up to 45 navigators";
  }
  const stochnav::testing::TempDir scratch;
  EXPECT_TRUE(azimuth_and_north_leave_three_sigma(
      east_west_rotary_80n_run(scratch, 1, {{"heading_hypothesis_sigma_deg", 0}}, "_one_filter")))
      << "one filter, seed 1";
  // Seed 3's failure with hypotheses that update their heading came with the vibration
  // episodes' false heading information, read by the full likelihood: with fix 7 (the
  // vibration in the model) it is inside, without it not (docs/drilling-envelope.md, section 4,
  // fix 7). With the weights' tempered likelihood (section 7) it is inside without fix 7 too.
  EXPECT_TRUE(azimuth_and_north_leave_three_sigma(east_west_rotary_80n_run(
      scratch, 3,
      {{"heading_hypothesis_consider", false},
       {"vibration_velocity_threshold_m_s", 0},
       {"heading_hypothesis_likelihood_power", 1.0}},
      "_heading_updated_no_vibration")))
      << "hypotheses that update their heading, without the vibration, seed 3";
  expect_every_station_inside(east_west_rotary_80n_run(
      scratch, 3, {{"heading_hypothesis_consider", false}}, "_heading_updated"));
}

// A bank that has not singled out a heading says so instead of looking healthy: sliding due
// east at 80 N, 5 min after the alignment, many hypotheses remain, and metrics.json's
// self-check reports the heading unresolved (docs/drilling-envelope.md, section 7).
TEST(DrillingEnvelope, AnUnresolvedHeadingIsReportedNotSilent) {
  if (!stochnav::testing::study_at_full_size()) {
    GTEST_SKIP() << "a bank of up to 45 navigators; the sanitizers run HeadingHypotheses in "
                    "filter_tests";
  }
  const stochnav::testing::TempDir scratch;
  const std::string out = simulate_and_run_from_field_start(
      scratch, "east_80n_sliding",
      {{"well", {{"azimuth_deg", 90}, {"kickoff_md_m", 100}}},
       {"start_md_m", 1000},
       {"rotation_rpm", 0},
       {"duration_s", 900}},
      {{"latitude_deg", 80}});
  const nlohmann::json heading = read_json(out + "/metrics.json")["self_check"]["heading"];
  EXPECT_FALSE(heading["resolved"].get<bool>()) << heading.dump();
  EXPECT_GT(heading["hypotheses"].get<int>(), 1) << heading.dump();
  EXPECT_LT(heading["largest_weight"].get<double>(), 0.9) << heading.dump();
}

// Axial vibration off the aids' reference (filter/velocity_oscillation.hpp, docs/
// drilling-envelope.md fix 7): sliding due east at 60 N through 10 min of 2.8 g at 8.37 Hz, whose
// cycles the 1-Hz ROP intervals cut. The ROP stays consistent (none rejected; before, 44-46 % at a
// mean NIS of 27-39), the azimuth stays inside its 3 sigma at every epoch after the alignment and
// the position at the end; without the vibration in the model (the ablation) the ROP is rejected
// and the along-hole (east) position ends 9.5 sigma off on seed 2.
double rop_rejected_share(const std::string& out) {
  const nlohmann::json metrics = read_json(out + "/metrics.json");
  for (const auto& aid : metrics["aids"]) {
    if (aid["type"] == "rop") return aid["rejected_share"].get<double>();
  }
  ADD_FAILURE() << "no rop in " << out << "/metrics.json";
  return 1.0;
}

TEST(DrillingEnvelope, AxialVibrationKeepsTheRopConsistentAndThePositionInside) {
  const stochnav::testing::TempDir scratch;
  const nlohmann::json drilling = {
      {"well", {{"azimuth_deg", 90}, {"kickoff_md_m", 100}}},
      {"start_md_m", 1000},
      {"rotation_rpm", 0},
      {"duration_s", 1500},
      {"vibration_episodes",
       {{{"start_s", 800}, {"end_s", 1400}, {"axial_g", 2.8}, {"frequency_hz", 8.37}}}}};
  const nlohmann::json site = {{"latitude_deg", 60}};
  for (const int seed : {2, 3}) {
    SCOPED_TRACE(seed);
    const std::string tag = "vibration_seed" + std::to_string(seed);
    const std::string out =
        simulate_and_run_from_field_start(scratch, tag, drilling, site, [](nlohmann::json&) {}, seed);
    EXPECT_LT(rop_rejected_share(out), 0.01);
    const auto errors = read_csv_columns(out + "/errors.csv");
    const auto& t = errors.at("t");
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] <= 700.0) continue;
      EXPECT_LE(std::abs(errors.at("azimuth_err_deg")[i]),
                3.0 * errors.at("azimuth_err_deg_sigma")[i])
          << "t " << t[i];
    }
    EXPECT_LE(end_error_sigmas(errors, "lat_err_m"), 3.0);
    EXPECT_LE(end_error_sigmas(errors, "lon_err_m"), 3.0);
    if (seed != 2) continue;
    const std::string ablation = simulate_and_run_from_field_start(
        scratch, tag, drilling, site,
        [](nlohmann::json& config) { config["filter"]["vibration_velocity_threshold_m_s"] = 0; },
        seed, "_ablation");
    EXPECT_GT(rop_rejected_share(ablation), 0.2);
    EXPECT_GT(end_error_sigmas(read_csv_columns(ablation + "/errors.csv"), "lon_err_m"), 3.0);
  }
}

// The survey QC without truth (experiment/station_qc.hpp) flags a run whose gyro model is
// deliberately wrong (a bias 25 times too well known, no bias walk): the azimuth and
// inclination leave their 3 sigma, and each connection's static solution says so.
void expect_wrong_gyro_model_flagged(const std::string& tag, const nlohmann::json& drilling,
                                     const nlohmann::json& site) {
  const stochnav::testing::TempDir scratch;
  nlohmann::json wrong_gyro = {{"plugin", "white"}, {"params", {{"N", 5.5e-4}, {"K", 0.01}}}};
  const std::string out =
      simulate_and_run_from_field_start(scratch, tag, drilling, site, [&](nlohmann::json& config) {
        config["noise"]["gyro"] = wrong_gyro;
        config["filter"]["initial_sigma"]["gyro_bias_deg_h"] = 0.02;
      });
  const nlohmann::json self_check = read_json(out + "/metrics.json")["self_check"];
  EXPECT_TRUE(self_check["optimistic"].get<bool>()) << self_check.dump();
  EXPECT_GT(self_check["survey_qc"]["flagged"].get<int>(), 0) << self_check.dump();
  EXPECT_NE(self_check["reason"].get<std::string>().find("survey QC"), std::string::npos);
}

TEST(DrillingEnvelope, SurveyQcFlagsAWrongGyroModelOnASlidingWell) {
  expect_wrong_gyro_model_flagged("slide_wrong",
                                  {{"rotation_rpm", 0}, {"duration_s", kWrongModelDuration_s}},
                                  nlohmann::json::object());
}

TEST(DrillingEnvelope, SurveyQcFlagsAWrongGyroModelInAnEastWestHole) {
  expect_wrong_gyro_model_flagged("east_wrong",
                                  {{"well", {{"azimuth_deg", 90}, {"kickoff_md_m", 100}}},
                                   {"start_md_m", 1000},
                                   {"duration_s", 14400}},
                                  {{"latitude_deg", 60}});
}

}  // namespace

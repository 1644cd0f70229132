// Unit tests of the diagnose domain: gap calibration, stationarity, signature, the loop.

#include "stochnav/diagnose/diagnose.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "diagnose_support.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/diagnose/gap.hpp"
#include "stochnav/diagnose/measured_statistics.hpp"
#include "stochnav/diagnose/report_json.hpp"
#include "stochnav/diagnose/signature.hpp"
#include "stochnav/diagnose/stationarity.hpp"
#include "stochnav/model/allan_variance.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

using diagnose_testing::natural;
using diagnose_testing::simulated_record;

constexpr double kRate = 100.0;

NoiseModel white_and_walk() {
  return {Unit::kDegPerHour,
          kRate,
          {AngleRandomWalkTerm{natural(ParameterDimension::kAnglePerRootTime, 0.5)},
           RateRandomWalkTerm{natural(ParameterDimension::kRatePerRootTime, 20.0)}}};
}

TEST(DiagnoseGap, IsAboutOneForRecordsOfTheModel) {
  const NoiseModel model = white_and_walk();
  double sum_avar = 0.0;
  double sum_stat = 0.0;
  double sum_gap = 0.0;
  const int seeds = 16;
  for (int seed = 1; seed <= seeds; ++seed) {
    const Record record = simulated_record(model, 100000, kRate, 100 + seed);
    const MeasuredStatistics measured = measure_record(record, 32);
    const Gap gap = combine_gap(avar_gap(model, measured.octave_avar),
                                stationarity_test(measured.windows, model), 1e-3);
    sum_avar += gap.avar.reduced_chi_square;
    sum_stat += gap.stationarity.reduced_chi_square;
    sum_gap += gap.value;
    EXPECT_GT(gap.avar.effective_dof, 3.0);
    EXPECT_LT(gap.avar.effective_dof, static_cast<double>(gap.avar.points.size()));
  }
  // Means over 16 records: each part is chi2(nu)/nu, nu >= 5, so the mean's sd is < 0.16.
  EXPECT_NEAR(sum_avar / seeds, 1.0, 0.35);
  EXPECT_NEAR(sum_stat / seeds, 1.0, 0.25);
  // The gap is the larger of two such parts: a little above 1 on average.
  EXPECT_GT(sum_gap / seeds, 0.9);
  EXPECT_LT(sum_gap / seeds, 1.5);
}

TEST(DiagnoseGap, IsScaleFree) {
  const NoiseModel model = white_and_walk();
  Record record = simulated_record(model, 50000, kRate, 3);
  const MeasuredStatistics measured = measure_record(record, 16);
  const Gap gap = combine_gap(avar_gap(model, measured.octave_avar),
                              stationarity_test(measured.windows, model), 1e-3);
  NoiseModel scaled = model;
  for (auto& term : scaled.terms) term = scale_amplitude(term, 7.0);
  for (double& value : record.values) value *= 7.0;
  const MeasuredStatistics measured_scaled = measure_record(record, 16);
  const Gap gap_scaled = combine_gap(avar_gap(scaled, measured_scaled.octave_avar),
                                     stationarity_test(measured_scaled.windows, scaled), 1e-3);
  EXPECT_NEAR(gap_scaled.value, gap.value, 1e-6 * gap.value);
}

TEST(DiagnoseGap, GrowsWithAMissingTerm) {
  NoiseModel truth = white_and_walk();
  truth.terms.push_back(GaussMarkovTerm{natural(ParameterDimension::kRate, 30.0), 5.0});
  const Record record = simulated_record(truth, 100000, kRate, 5);
  const MeasuredStatistics measured = measure_record(record, 32);
  const AvarGap gap = avar_gap(white_and_walk(), measured.octave_avar);
  EXPECT_GT(gap.reduced_chi_square, 10.0);
}

TEST(DiagnoseEffectiveModel, AveragesTheSegmentScale) {
  NoiseModel model = white_and_walk();
  model.terms.push_back(NonstationaryTerm{{{100.0, 200.0, 3.0}}});
  const StationaryEquivalent equivalent = stationary_equivalent(model, 1000.0);
  // w = 0.9 + 0.1 * 9 = 1.8; fourth moment 0.9 + 0.1 * 81 = 9; kappa = 9 / 3.24.
  EXPECT_NEAR(equivalent.variance_factor, 1.8, 1e-12);
  EXPECT_NEAR(equivalent.variance_inflation, 9.0 / 3.24, 1e-12);
  EXPECT_EQ(equivalent.model.terms.size(), 2u);
  EXPECT_NEAR(allan_variance(equivalent.model, 1.0), 1.8 * allan_variance(white_and_walk(), 1.0),
              1e-12 * allan_variance(equivalent.model, 1.0));
  EXPECT_NEAR(mean_scale_squared(model, 150.0, 250.0), 0.5 * 9.0 + 0.5, 1e-12);
}

TEST(DiagnoseStationarity, FindsALoudStretchAndItsScale) {
  NoiseModel truth = white_and_walk();
  truth.terms.push_back(NonstationaryTerm{{{400.0, 600.0, 2.5}}});
  const Record record = simulated_record(truth, 100000, kRate, 11);
  const MeasuredStatistics measured = measure_record(record, 20);  // 50 s windows
  const StationarityTest test = stationarity_test(measured.windows, white_and_walk());
  EXPECT_LT(test.p_value, 1e-6);
  for (std::size_t k = 0; k < test.deviating.size(); ++k) {
    const bool inside = measured.windows.start_s[k] >= 400.0 && measured.windows.end_s[k] <= 600.0;
    EXPECT_EQ(test.deviating[k], inside) << "window " << k;
  }
  const auto term = nonstationary_candidate(measured.windows, test, white_and_walk());
  ASSERT_TRUE(term.has_value());
  ASSERT_EQ(term->segments.size(), 1u);
  EXPECT_NEAR(term->segments[0].start_s, 400.0, 1e-9);
  EXPECT_NEAR(term->segments[0].end_s, 600.0, 1e-9);
  EXPECT_NEAR(term->segments[0].scale, 2.5, 0.1);
  // The model with that term makes the windows agree.
  NoiseModel fixed = white_and_walk();
  fixed.terms.push_back(*term);
  EXPECT_GT(stationarity_test(measured.windows, fixed).p_value, 1e-3);
}

TEST(DiagnoseStationarity, PlacesAnEdgeInsideAPartlyCoveredWindow) {
  NoiseModel truth = white_and_walk();
  truth.terms.push_back(NonstationaryTerm{{{420.0, 630.0, 3.0}}});
  const Record record = simulated_record(truth, 100000, kRate, 12);
  const MeasuredStatistics measured = measure_record(record, 20);  // 50 s windows
  const StationarityTest test = stationarity_test(measured.windows, white_and_walk());
  const auto term = nonstationary_candidate(measured.windows, test, white_and_walk());
  ASSERT_TRUE(term.has_value());
  ASSERT_EQ(term->segments.size(), 1u);
  EXPECT_NEAR(term->segments[0].start_s, 420.0, 5.0);
  EXPECT_NEAR(term->segments[0].end_s, 630.0, 5.0);
  EXPECT_NEAR(term->segments[0].scale, 3.0, 0.1);
}

TEST(DiagnoseStationarity, AStationaryRecordPasses) {
  int failures = 0;
  for (int seed = 1; seed <= 10; ++seed) {
    const Record record = simulated_record(white_and_walk(), 100000, kRate, 40 + seed);
    const MeasuredStatistics measured = measure_record(record, 32);
    const StationarityTest test = stationarity_test(measured.windows, white_and_walk());
    if (test.p_value < 1e-3) ++failures;
    EXPECT_TRUE(
        std::none_of(test.deviating.begin(), test.deviating.end(), [](bool d) { return d; }));
  }
  EXPECT_EQ(failures, 0);
}

// A measured curve equal to the closed form of model + extra: the signature names the extra.
Signature signature_of(const NoiseModel& model, const NoiseTerm& extra) {
  NoiseModel truth = model;
  truth.terms.push_back(extra);
  const std::size_t phase_count = 1000001;
  AvarMeasurement measured;
  measured.phase_count = phase_count;
  measured.tau0_s = 1.0 / kRate;
  std::vector<double> dense_tau, dense_avar, dense_edf;
  for (std::size_t m = 1; 4 * m < phase_count; m *= 2) {
    measured.m.push_back(m);
    measured.tau_s.push_back(static_cast<double>(m) / kRate);
    measured.avar.push_back(allan_variance(truth, measured.tau_s.back()));
  }
  for (double k = 0;; k += 1.0) {
    const double m = std::round(std::pow(10.0, k / 20.0));
    if (4.0 * m >= static_cast<double>(phase_count)) break;
    if (!dense_tau.empty() && m / kRate <= dense_tau.back()) continue;
    dense_tau.push_back(m / kRate);
    dense_avar.push_back(allan_variance(truth, m / kRate));
    dense_edf.push_back(static_cast<double>(phase_count) / m);  // about white noise's
  }
  return read_signature(avar_gap(model, measured), dense_tau, dense_avar, dense_edf, model);
}

TEST(DiagnoseSignature, NamesPowerLawsBumpsAndLines) {
  const NoiseModel base{Unit::kDegPerHour,
                        kRate,
                        {AngleRandomWalkTerm{natural(ParameterDimension::kAnglePerRootTime, 0.5)},
                         BiasInstabilityTerm{natural(ParameterDimension::kRate, 1.0)}}};
  EXPECT_EQ(
      signature_of(base, RateRandomWalkTerm{natural(ParameterDimension::kRatePerRootTime, 10.0)})
          .suggested,
      TermType::kRateRandomWalk);
  EXPECT_EQ(
      signature_of(base, RateRampTerm{natural(ParameterDimension::kRatePerTime, 20.0)}).suggested,
      TermType::kRateRamp);
  EXPECT_EQ(
      signature_of(base, QuantizationTerm{natural(ParameterDimension::kAngle, 5.0)}).suggested,
      TermType::kQuantization);
  EXPECT_EQ(
      signature_of(base, GaussMarkovTerm{natural(ParameterDimension::kRate, 20.0), 5.0}).suggested,
      TermType::kGaussMarkov);
  EXPECT_EQ(signature_of(base, SinusoidTerm{natural(ParameterDimension::kRate, 200.0), 0.05, {}})
                .suggested,
            TermType::kSinusoid);
  const Signature walk =
      signature_of(base, RateRandomWalkTerm{natural(ParameterDimension::kRatePerRootTime, 10.0)});
  ASSERT_TRUE(walk.tau_range_s.has_value());
  EXPECT_TRUE(walk.above);
  EXPECT_GT((*walk.tau_range_s)[0], 10.0);
}

TEST(Diagnose, AConsistentModelGetsNoIterations) {
  const Record record = simulated_record(white_and_walk(), 100000, kRate, 21);
  DiagnoseOptions options;
  options.seeds = 0;
  const DiagnoseResult result = diagnose(record, white_and_walk(), options);
  EXPECT_TRUE(result.consistent);
  EXPECT_TRUE(result.iterations.empty());
  const auto json = diagnose_report_json(result);
  EXPECT_TRUE(json["iterations"].empty());
  EXPECT_EQ(json["gap_initial"], json["gap_final"]);
}

TEST(Diagnose, FindsAHiddenGaussMarkovTermAndTheGapShrinks) {
  NoiseModel truth = white_and_walk();
  truth.terms.push_back(GaussMarkovTerm{natural(ParameterDimension::kRate, 40.0), 4.0});
  const Record record = simulated_record(truth, 200000, kRate, 8);
  DiagnoseOptions options;
  options.seeds = 2;
  const DiagnoseResult result = diagnose(record, white_and_walk(), options);
  ASSERT_FALSE(result.iterations.empty());
  const DiagnoseIteration& step = result.iterations.front();
  EXPECT_EQ(step.effect, TermType::kGaussMarkov);
  EXPECT_LT(step.gap_after, 0.2 * step.gap_before);
  ASSERT_TRUE(step.tau_range_s.has_value());
  EXPECT_LT((*step.tau_range_s)[0], 8.0);
  EXPECT_GT((*step.tau_range_s)[1], 8.0);
  const auto* added = std::get_if<GaussMarkovTerm>(&step.added_term);
  ASSERT_NE(added, nullptr);
  EXPECT_NEAR(added->tau_c, 4.0, 2.0);
  EXPECT_TRUE(result.consistent);
  EXPECT_EQ(result.final_assessment().band.low.size(), result.final_assessment().band.tau_s.size());
}

TEST(Diagnose, RejectsAModelOfAnotherQuantity) {
  Record record = simulated_record(white_and_walk(), 10000, kRate, 1);
  record.unit = Unit::kMeterPerSecondSquared;
  EXPECT_THROW(diagnose(record, white_and_walk()), ConfigError);
}

}  // namespace
}  // namespace stochnav

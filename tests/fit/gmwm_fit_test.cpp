// GMWM (fit/gmwm_fit.hpp): known truth over many simulated seeds (coverage and bias of the
// estimates and their delta-method uncertainties), the real ADIS16405 gyro (objective, J-test,
// lag-1 correlation held by the AR1 term), the `wv` package's tables as input, and bad input.

#include "stochnav/fit/gmwm_fit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/fit/implied_wavelet_variance.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/sim/noise_generator.hpp"
#include "stochnav/stats/wavelet_variance.hpp"

namespace stochnav {
namespace {

const std::string kData = STOCHNAV_SHARED_DATA_DIR;

GmwmData simulated_wavelet_variance(const NoiseModel& model, std::size_t samples,
                                    std::uint64_t seed) {
  NoiseGenerator generator(model, model.rate_hz, seed,
                           static_cast<double>(samples) / model.rate_hz);
  std::vector<double> rate(samples);
  generator.generate(rate);
  return gmwm_data_from_levels(haar_wavelet_variance(rate, model.rate_hz), Unit::kPlain,
                               model.rate_hz, "simulated");
}

/// Per fitted parameter (model order, parameter_specs order): how often the 95 % interval
/// value +/- 1.96 sigma held the truth, and the median of estimate / truth.
struct ParameterStatistics {
  std::vector<double> coverage;
  std::vector<double> median_ratio;
  double j_rejected_5pc = 0.0;  ///< fraction of seeds whose J-test p < 0.05
};

ParameterStatistics simulate_and_fit(const NoiseModel& truth, std::size_t samples, int seeds) {
  std::vector<TermType> types;
  std::vector<double> true_values;
  for (const auto& term : truth.terms) {
    types.push_back(term_type(term));
    for (std::size_t k = 0; k < parameter_specs(term_type(term)).size(); ++k) {
      true_values.push_back(*parameter_value(term, k));
    }
  }
  std::vector<std::vector<double>> ratios(true_values.size());
  std::vector<int> covered(true_values.size(), 0);
  int rejected = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const FitResult fit = fit_gmwm(simulated_wavelet_variance(truth, samples, seed),
                                   {.terms = types});
    std::size_t i = 0;
    for (std::size_t t = 0; t < fit.model.terms.size(); ++t) {
      for (std::size_t k = 0; k < parameter_specs(types[t]).size(); ++k, ++i) {
        const double value = *parameter_value(fit.model.terms[t], k);
        const double sigma = *parameter_value(fit.sigma[t], k);
        ratios[i].push_back(value / true_values[i]);
        // The interval in the log domain, where the delta method was made.
        const double half = 1.96 * sigma / value;
        if (std::abs(std::log(value / true_values[i])) <= half) ++covered[i];
      }
    }
    if (fit.diagnostics.chi_square_p_value() < 0.05) ++rejected;
  }
  ParameterStatistics out;
  for (std::size_t i = 0; i < true_values.size(); ++i) {
    out.coverage.push_back(static_cast<double>(covered[i]) / seeds);
    auto& r = ratios[i];
    std::nth_element(r.begin(), r.begin() + static_cast<long>(r.size() / 2), r.end());
    out.median_ratio.push_back(r[r.size() / 2]);
  }
  out.j_rejected_5pc = static_cast<double>(rejected) / seeds;
  return out;
}

TEST(GmwmFit, ImpliedWaveletVarianceIsHalfTheAllanVarianceAtHalfTheScale) {
  const double one = 1.0;
  // N^2 / tau, K^2 tau / 12, 6 Q^2 / tau^2, R^2 tau^2 / 16.
  EXPECT_DOUBLE_EQ(term_wavelet_variance(TermType::kAngleRandomWalk, &one, 4.0), 0.25);
  EXPECT_DOUBLE_EQ(term_wavelet_variance(TermType::kRateRandomWalk, &one, 4.0), 4.0 / 12.0);
  EXPECT_DOUBLE_EQ(term_wavelet_variance(TermType::kQuantization, &one, 2.0), 6.0 / 4.0);
  EXPECT_DOUBLE_EQ(term_wavelet_variance(TermType::kRateRamp, &one, 2.0), 4.0 / 16.0);
}

TEST(GmwmFit, WhiteNoiseAr1RandomWalkHasCoverageAndSmallBiasOverSeeds) {
  // White + AR1 (tau_c 0.5 s) + random walk at 100 Hz, 2^18 samples (44 min), 40 seeds.
  const NoiseModel truth{Unit::kPlain, 100.0,
                         {AngleRandomWalkTerm{1e-3}, GaussMarkovTerm{2e-3, 0.5},
                          RateRandomWalkTerm{2e-5}}};
  const auto stats = simulate_and_fit(truth, std::size_t{1} << 18, 40);
  const char* names[] = {"N", "GM sigma", "GM tau_c", "K"};
  for (std::size_t i = 0; i < stats.coverage.size(); ++i) {
    // Stated bounds: nominal 95 % coverage, at least 80 % over 40 seeds (the diagonal Omega
    // ignores the correlation between scales); median within 10 % of the truth, except K
    // (measured 0.83): its few top scales are weighted by their own estimates (Omega from the
    // intervals of nu_hat), which favours low values; within 35 %.
    EXPECT_GE(stats.coverage[i], 0.80) << names[i];
    EXPECT_NEAR(stats.median_ratio[i], 1.0, i == 3 ? 0.35 : 0.10) << names[i];
    std::printf("[evidence] WN+AR1+RW %-9s coverage %.3f median est/truth %.3f\n", names[i],
                stats.coverage[i], stats.median_ratio[i]);
  }
  std::printf("[evidence] WN+AR1+RW J-test rejects at 5 %%: %.3f of seeds\n", stats.j_rejected_5pc);
  EXPECT_LE(stats.j_rejected_5pc, 0.25);
}

TEST(GmwmFit, WhiteNoiseTwoAr1RandomWalkFindsBothCorrelationTimes) {
  // Two AR1 a decade and a half apart (0.05 s and 5 s): the grid starts must not let either
  // collapse to a short correlation time. 2^19 samples at 100 Hz, 30 seeds.
  const NoiseModel truth{Unit::kPlain, 100.0,
                         {AngleRandomWalkTerm{1e-3}, GaussMarkovTerm{4e-3, 0.05},
                          GaussMarkovTerm{1e-3, 5.0}, RateRandomWalkTerm{2e-5}}};
  const auto stats = simulate_and_fit(truth, std::size_t{1} << 19, 30);
  const char* names[] = {"N", "GM1 sigma", "GM1 tau_c", "GM2 sigma", "GM2 tau_c", "K"};
  for (std::size_t i = 0; i < stats.coverage.size(); ++i) {
    // Stated bounds with six parameters: coverage >= 80 %, median within 10 %, K (measured
    // 0.72, see above) within 40 %.
    EXPECT_GE(stats.coverage[i], 0.80) << names[i];
    EXPECT_NEAR(stats.median_ratio[i], 1.0, i == 5 ? 0.40 : 0.10) << names[i];
    std::printf("[evidence] WN+2AR1+RW %-9s coverage %.3f median est/truth %.3f\n", names[i],
                stats.coverage[i], stats.median_ratio[i]);
  }
  std::printf("[evidence] WN+2AR1+RW J-test rejects at 5 %%: %.3f of seeds\n",
              stats.j_rejected_5pc);
}

/// The lag-1 correlation of the interval means of white noise plus Gauss-Markov terms.
double model_lag1_correlation(const NoiseModel& model) {
  const double tau0 = 1.0 / model.rate_hz;
  double variance = 0.0;
  double covariance = 0.0;
  for (const auto& term : model.terms) {
    if (const auto* n = std::get_if<AngleRandomWalkTerm>(&term)) variance += n->n * n->n / tau0;
    if (const auto* g = std::get_if<GaussMarkovTerm>(&term)) {
      const double h = tau0 / g->tau_c;
      const double scale = g->sigma * g->sigma * g->tau_c * g->tau_c / (tau0 * tau0);
      variance += 2.0 * scale * closed_form::ou_integral_shape(h);
      covariance += scale * (1.0 - std::exp(-h)) * (1.0 - std::exp(-h));
    }
  }
  return covariance / variance;
}

TEST(GmwmFit, AdisGyroXIsDescribedByWhiteNoiseAr1AndRandomWalk) {
  const std::string path = kData + "/imu-static/adis16405_imu1_static_100hz.csv";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " absent (../shared/data)";
  const Record record = read_record({.path = path, .column = "gyro_x_dps",
                                     .unit = Unit::kDegPerSecond});
  const GmwmData data = gmwm_data_from_levels(haar_wavelet_variance(record.values, 100.0),
                                              record.unit, 100.0, path);
  const FitResult fit =
      fit_gmwm(data, {.terms = {TermType::kAngleRandomWalk, TermType::kGaussMarkov,
                                TermType::kRateRandomWalk}});
  const auto& d = fit.diagnostics;
  std::printf("[evidence] ADIS gyro X GMWM ARW+GM+RW: objective %.4g for %zu dof, J-test p %.3g\n",
              d.chi_square, d.points - d.parameters, d.chi_square_p_value());
  for (std::size_t t = 0; t < fit.model.terms.size(); ++t) {
    for (std::size_t k = 0; k < parameter_specs(term_type(fit.model.terms[t])).size(); ++k) {
      std::printf("[evidence]   %s.%s = %.6g (sd %.3g, natural units)\n",
                  std::string(term_type_name(term_type(fit.model.terms[t]))).c_str(),
                  std::string(parameter_specs(term_type(fit.model.terms[t]))[k].name).c_str(),
                  *parameter_value(fit.model.terms[t], k), *parameter_value(fit.sigma[t], k));
    }
  }
  // The Allan-variance fit of the same model gave chi-square 5.2e4 for 16 dof (issue #30): the
  // GMWM objective (measured 26.7 for 14 dof) passes the J-test at 1 %.
  EXPECT_GT(d.chi_square_p_value(), 0.01);
  EXPECT_LT(d.reduced_chi_square(), 5.2e4 / 16 / 100);
  // What the record says, found here and kept honest: the AR1 has a correlation time of about a
  // quarter of the sampling interval (measured 2.6 ms) and carries the white noise with it; the
  // separate white-noise term goes to its lower bound (the two trade off along a flat valley,
  // gmwm_fit.hpp: kGmwmMinCorrelationTimeSamples). A fit flagged so is refused by the CLI
  // without --keep-failed.
  EXPECT_EQ(d.at_bound, std::vector<std::string>{"angle_random_walk.N"});
  // The record's lag-1 correlation (0.17) is what the white noise + AR1 part implies.
  const auto& y = record.values;
  const double mean = std::accumulate(y.begin(), y.end(), 0.0) / static_cast<double>(y.size());
  double c0 = 0.0, c1 = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    c0 += (y[i] - mean) * (y[i] - mean);
    if (i + 1 < y.size()) c1 += (y[i] - mean) * (y[i + 1] - mean);
  }
  const double model_rho = model_lag1_correlation(fit.model);
  std::printf("[evidence] ADIS lag-1 correlation: record %.4f, fitted model %.4f\n", c1 / c0,
              model_rho);
  EXPECT_NEAR(c1 / c0, 0.17, 0.02);
  EXPECT_NEAR(model_rho, c1 / c0, 0.04);
}

TEST(GmwmFit, FitsTheWvPackagesTables) {
  for (const char* name : {"navchip", "ln200"}) {
    const std::string path = kData + "/gmwm/" + name + "_wv_ref.csv";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " absent (../shared/data)";
    const GmwmData data = read_wavelet_variance_table(path, "Gyro. X", Unit::kRadPerSecond, 0.0);
    EXPECT_GT(data.rate_hz, 0.0);
    const FitResult fit =
        fit_gmwm(data, {.terms = {TermType::kAngleRandomWalk, TermType::kGaussMarkov,
                                  TermType::kRateRandomWalk}});
    std::printf("[evidence] %s Gyro. X ARW+GM+RW: objective %.4g for %zu dof\n", name,
                fit.diagnostics.chi_square, fit.diagnostics.points - fit.diagnostics.parameters);
    EXPECT_TRUE(std::isfinite(fit.diagnostics.chi_square));
    // A second AR1 is nested: its optimum can only be lower (the starts must find it).
    const FitResult richer =
        fit_gmwm(data, {.terms = {TermType::kAngleRandomWalk, TermType::kGaussMarkov,
                                  TermType::kGaussMarkov, TermType::kRateRandomWalk}});
    std::printf("[evidence] %s Gyro. X ARW+2GM+RW: objective %.4g for %zu dof\n", name,
                richer.diagnostics.chi_square,
                richer.diagnostics.points - richer.diagnostics.parameters);
    EXPECT_LT(richer.diagnostics.chi_square, fit.diagnostics.chi_square * 1.0001);
  }
}

GmwmData white_noise_data(std::size_t samples) {
  return simulated_wavelet_variance({Unit::kPlain, 100.0, {AngleRandomWalkTerm{1e-3}}}, samples,
                                    7);
}

TEST(GmwmFit, BadInputIsRefusedWithOneLine) {
  GmwmData two = white_noise_data(1000);
  two.scale_s.resize(2);
  two.wv.resize(2);
  two.wv_lo.resize(2);
  two.wv_hi.resize(2);
  EXPECT_THROW(fit_gmwm(two, {.terms = {TermType::kAngleRandomWalk}}), InputError);
  GmwmData constant = white_noise_data(1000);
  std::fill(constant.wv.begin(), constant.wv.end(), 0.0);
  EXPECT_THROW(fit_gmwm(constant, {.terms = {TermType::kAngleRandomWalk}}), InputError);
  const GmwmOptions same_tau{
      .terms = {TermType::kAngleRandomWalk, TermType::kGaussMarkov, TermType::kGaussMarkov},
      .controls = {{.term = 1, .parameter = 1, .start = 2.0},
                   {.term = 2, .parameter = 1, .start = 2.0}}};
  EXPECT_THROW(fit_gmwm(white_noise_data(100000), same_tau), ConfigError);
  // 128 samples: 6 scales, too few for a drift.
  EXPECT_THROW(fit_gmwm(white_noise_data(128),
                        {.terms = {TermType::kAngleRandomWalk, TermType::kRateRamp}}),
               ConfigError);
  EXPECT_THROW(fit_gmwm(white_noise_data(100000), {.terms = {TermType::kSinusoid}}), ConfigError);
}

TEST(GmwmFit, FixedCorrelationTimeIsHeldAndStartsSteer) {
  const NoiseModel truth{Unit::kPlain, 100.0,
                         {AngleRandomWalkTerm{1e-3}, GaussMarkovTerm{2e-3, 0.5}}};
  const GmwmData data = simulated_wavelet_variance(truth, std::size_t{1} << 17, 3);
  const FitResult fit =
      fit_gmwm(data, {.terms = {TermType::kAngleRandomWalk, TermType::kGaussMarkov},
                      .controls = {{.term = 1, .parameter = 1, .fixed = 0.7}}});
  EXPECT_DOUBLE_EQ(std::get<GaussMarkovTerm>(fit.model.terms[1]).tau_c, 0.7);
  EXPECT_EQ(std::get<GaussMarkovTerm>(fit.sigma[1]).tau_c, 0.0);
  EXPECT_EQ(fit.diagnostics.parameters, 2u);
}

TEST(GmwmFit, RankingPrefersTheTrueModelByWic) {
  const NoiseModel truth{Unit::kPlain, 100.0,
                         {AngleRandomWalkTerm{1e-3}, GaussMarkovTerm{2e-3, 0.5},
                          RateRandomWalkTerm{2e-5}}};
  const GmwmData data = simulated_wavelet_variance(truth, std::size_t{1} << 18, 11);
  const std::vector<std::vector<TermType>> candidates = {
      {TermType::kAngleRandomWalk, TermType::kRateRandomWalk},
      {TermType::kAngleRandomWalk, TermType::kGaussMarkov, TermType::kRateRandomWalk},
      {TermType::kAngleRandomWalk}};
  const auto ranked = rank_gmwm_models(data, candidates, {});
  ASSERT_EQ(ranked.front().ranking.size(), 3u);
  EXPECT_EQ(ranked.front().ranking.front().terms, candidates[1]);
  EXPECT_LE(ranked.front().ranking[0].wic, ranked.front().ranking[1].wic);
}

}  // namespace
}  // namespace stochnav

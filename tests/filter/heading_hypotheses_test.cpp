// The bank of filters over the heading: its split start is the start distribution (mean and
// covariance); after a static alignment it is the gyrocompass's exact posterior over the whole
// circle (every hypothesis explains the measured rate, and the truth falls in its credible
// intervals as often as they claim); a start whose heading is known is one plain filter with
// identical outputs; the core error-state difference and its feedback are inverse to each other.

#include "stochnav/filter/heading_hypotheses.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "stochnav/filter/alignment.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"

#include "static_truth.hpp"

namespace stochnav {
namespace {

using testing::kDeg;
using testing::NoisyStaticAid;
using testing::StaticImu;
using testing::TestWhiteNoise;

constexpr int kHeading = plugin::core_state::kAttitude + 2;
constexpr int kGyroBiasX = plugin::core_state::kGyroBias;

NavigatorPlugins white_noise_plugins(const NavState& site, std::uint64_t seed) {
  return {std::make_shared<TestWhiteNoise>(plugin::SensorGroup::kGyro, 0.01 * kDeg / 60.0),
          std::make_shared<TestWhiteNoise>(plugin::SensorGroup::kAccel, 0.01 / 60.0),
          {std::make_shared<NoisyStaticAid>(site, 0.05, 0.002, seed)}};
}

// A start with the heading uncertain by `heading_sigma` and correlated with the x gyro bias
// (as a gyrocompass leaves them: correlation 0.9).
FilterOptions uncertain_heading_start(double heading_sigma) {
  FilterOptions options;
  options.attitude_sigma_rad.z() = heading_sigma;
  Eigen::Matrix<double, 15, 1> sigma;
  sigma << options.position_sigma_m, options.velocity_sigma_mps, options.attitude_sigma_rad,
      options.accel_bias_sigma_mps2, options.gyro_bias_sigma_radps;
  Eigen::Matrix<double, 15, 15> p = sigma.array().square().matrix().asDiagonal();
  p(kHeading, kGyroBiasX) = p(kGyroBiasX, kHeading) = 0.9 * sigma(kHeading) * sigma(kGyroBiasX);
  options.initial_core_covariance = p;
  return options;
}

TEST(CoreCorrection, DifferenceFedBackGivesTheReference) {
  const NavState site = testing::static_truth_state();
  CoreEstimate reference{site, Eigen::Vector3d(1e-4, -2e-4, 3e-4),
                         Eigen::Vector3d(1e-6, 2e-6, -3e-6)};
  CoreEstimate estimate = reference;
  estimate.state.latitude_rad += 2e-6;
  estimate.state.longitude_rad -= 3e-6;
  estimate.state.height_m += 4.0;
  estimate.state.v_n += Eigen::Vector3d(0.1, -0.2, 0.05);
  estimate.state.q_nb =
      Eigen::Quaterniond(
          Eigen::AngleAxisd(40.0 * kDeg, Eigen::Vector3d(0.1, 0.2, 1.0).normalized())) *
      estimate.state.q_nb;
  estimate.gyro_bias_b += Eigen::Vector3d(3e-6, 0.0, -1e-6);
  estimate.accel_bias_b -= Eigen::Vector3d(0.0, 2e-4, 0.0);

  const Eigen::Matrix<double, 15, 1> x = core_difference(estimate, reference);
  // The estimate is the reference rotated by +40 deg: C_ref = Rot(phi) C_est gives phi = -40 deg
  // about that axis.
  EXPECT_NEAR(x(kHeading), -40.0 * kDeg * Eigen::Vector3d(0.1, 0.2, 1.0).normalized().z(),
              1e-12);
  CoreEstimate corrected = estimate;
  apply_core_correction(x, corrected);
  // Position to first order: the radii of the two latitudes differ (1e-11 rad: 0.06 mm).
  EXPECT_NEAR(corrected.state.latitude_rad, reference.state.latitude_rad, 1e-11);
  EXPECT_NEAR(corrected.state.longitude_rad, reference.state.longitude_rad, 1e-11);
  EXPECT_NEAR(corrected.state.height_m, reference.state.height_m, 1e-9);
  EXPECT_LT((corrected.state.v_n - reference.state.v_n).norm(), 1e-12);
  EXPECT_LT(corrected.state.q_nb.angularDistance(reference.state.q_nb), 1e-12);
  EXPECT_LT((corrected.gyro_bias_b - reference.gyro_bias_b).norm(), 1e-18);
  EXPECT_LT((corrected.accel_bias_b - reference.accel_bias_b).norm(), 1e-16);
}

TEST(HeadingHypotheses, AKnownHeadingIsOnePlainFilterWithTheSameOutputs) {
  const NavState site = testing::static_truth_state();
  const FilterOptions options;  // heading sigma 0.57 deg
  NavigatorPlugins plain_plugins = white_noise_plugins(site, 7);
  MwdNavigator plain(site, *plain_plugins.gyro, *plain_plugins.accel,
                     {plain_plugins.aids.front().get()}, options);
  HeadingHypotheses bank(site, options, white_noise_plugins(site, 7),
                         [&] { return white_noise_plugins(site, 7); });
  ASSERT_EQ(bank.hypotheses(), 1u);
  StaticImu imu(site, {.gyro_arw = 0.01 * kDeg / 60.0, .accel_vrw = 0.01 / 60.0}, 100.0, 3);
  for (int k = 0; k < 2000; ++k) {
    const ImuIncrement increment = imu.next();
    plain.step(increment);
    bank.step(increment);
  }
  EXPECT_EQ(bank.state().q_nb.coeffs(), plain.state().q_nb.coeffs());
  EXPECT_EQ(bank.state().v_n, plain.state().v_n);
  EXPECT_EQ(bank.gyro_bias_b(), plain.gyro_bias_b());
  EXPECT_EQ(bank.covariance(), plain.covariance());
  EXPECT_EQ(bank.innovations().size(), plain.innovations().size());
}

TEST(HeadingHypotheses, TheSplitStartHasTheStartsMeanAndCovariance) {
  const NavState site = testing::static_truth_state();
  for (const double sigma_deg : {12.0, 20.0}) {
    const FilterOptions options = uncertain_heading_start(sigma_deg * kDeg);
    HeadingHypotheses bank(site, options, white_noise_plugins(site, 1),
                           [&] { return white_noise_plugins(site, 1); });
    // A grid 2 x 4 deg apart over +-3 sigma (at most 15).
    EXPECT_EQ(bank.hypotheses(), sigma_deg == 12.0 ? 11u : 15u) << sigma_deg;
    const Eigen::Matrix<double, 15, 15> p0 = *options.initial_core_covariance;
    const Eigen::MatrixXd& p = bank.covariance();
    ASSERT_EQ(p.rows(), 15);
    // The grid's truncation at +-3 sigma (2.8 sigma for 20 deg) loses a few % of the variance.
    EXPECT_NEAR(p(kHeading, kHeading) / p0(kHeading, kHeading), 1.0, 0.05) << sigma_deg;
    EXPECT_NEAR(p(kHeading, kGyroBiasX) / p0(kHeading, kGyroBiasX), 1.0, 0.05) << sigma_deg;
    EXPECT_NEAR(p(kGyroBiasX, kGyroBiasX) / p0(kGyroBiasX, kGyroBiasX), 1.0, 0.05) << sigma_deg;
    for (int i = 0; i < 15; ++i) {
      if (i == kHeading || i == kGyroBiasX) continue;
      EXPECT_NEAR(p(i, i) / p0(i, i), 1.0, 1e-9) << "state " << i << ", " << sigma_deg;
    }
    EXPECT_LT(bank.state().q_nb.angularDistance(site.q_nb), 1e-9) << sigma_deg;
    // The weight near the most probable (middle) one: itself alone within 1 deg, with its two
    // neighbours (8 deg away) within 9 deg, all within 90 deg.
    EXPECT_NEAR(bank.weight_within_rad(1.0 * kDeg), bank.largest_weight(), 1e-12) << sigma_deg;
    EXPECT_NEAR(bank.weight_within_rad(9.0 * kDeg),
                bank.largest_weight() + bank.weight(1) + bank.weight(2), 1e-12)
        << sigma_deg;
    EXPECT_NEAR(bank.weight_within_rad(90.0 * kDeg), 1.0, 1e-12) << sigma_deg;
    // The middle hypothesis' prior weight: about the grid spacing times the density of the
    // remaining spread, N(0, sigma^2 - 4^2), at zero.
    const double spread_deg = std::sqrt(sigma_deg * sigma_deg - 16.0);
    EXPECT_NEAR(bank.largest_weight(), 8.0 / (std::sqrt(2.0 * std::numbers::pi) * spread_deg),
                0.01)
        << sigma_deg;
  }
}

// Below 10 deg of start sigma one filter is formed, unless the tool rotates with its +-3 sigma
// headings across the east-west line and its axis above 60 deg of inclination (at any heading
// sigma above a quarter of a degree): there the rotating cross-axis gyros cannot tell psi from
// 180 deg - psi, and one linearised filter that starts on the other side of the line from the
// truth settles near the mirror (docs/drilling-envelope.md, section 7). Whether the tool rotates
// is not known at the start, so the mirror's bank forms once the tool has turned a full turn
// (here spinning at 60 rpm from the start: after 1 s); under the ablation
// (FilterOptions::heading_hypotheses_mirror_at_rotation false) at the start.
TEST(HeadingHypotheses, ARotatingToolWithinReachOfTheEastWestMirrorFormsABank) {
  struct Start {
    double inclination_deg, azimuth_deg, sigma_deg;
    bool bank;
  };
  for (const Start& c : {Start{82.0, 87.0, 7.0, true}, Start{82.0, 267.0, 7.0, true},
                         Start{62.0, 110.0, 7.0, true}, Start{82.0, 60.0, 7.0, false},
                         Start{82.0, 120.0, 7.0, false}, Start{55.0, 90.0, 7.0, false},
                         Start{82.0, 90.0, 3.5, true}, Start{82.0, 94.0, 1.5, true},
                         Start{82.0, 90.0, 0.2, false}, Start{82.0, 99.0, 2.5, false},
                         Start{30.0, 0.0, 12.0, true}}) {
    NavState site = testing::static_truth_state();
    site.q_nb = quaternion_from_mwd({.inclination_rad = c.inclination_deg * kDeg,
                                     .toolface_rad = 0.0,
                                     .azimuth_rad = c.azimuth_deg * kDeg});
    const bool wide = c.sigma_deg > 10.0;
    FilterOptions options = uncertain_heading_start(c.sigma_deg * kDeg);
    HeadingHypotheses bank(site, options, white_noise_plugins(site, 1),
                           [&] { return white_noise_plugins(site, 1); });
    const auto start = [&] {
      return "inclination " + std::to_string(c.inclination_deg) + ", azimuth " +
             std::to_string(c.azimuth_deg) + ", sigma " + std::to_string(c.sigma_deg);
    };
    EXPECT_EQ(bank.initial_hypotheses() > 1, wide) << start();
    StaticImu imu(site, {}, testing::kRateHz, 1, 2.0 * std::numbers::pi);
    for (int k = 0; k < 90; ++k) bank.step(imu.next());
    EXPECT_EQ(bank.splits(), 0u) << "before a full turn: " << start();
    for (int k = 0; k < 30; ++k) bank.step(imu.next());
    EXPECT_EQ(bank.splits() > 0 || wide, c.bank) << start();
    options.heading_hypotheses_mirror_at_rotation = false;
    HeadingHypotheses ablation(site, options, white_noise_plugins(site, 1),
                               [&] { return white_noise_plugins(site, 1); });
    EXPECT_EQ(ablation.initial_hypotheses() > 1, c.bank) << "ablation, " << start();
  }
}

// A tool at the site turning about its axis: feed() gives `bank` `seconds` of it at `spin`
// rad/s, continuing the truth's toolface and the record's time from where the last feed left
// them.
struct TurningTool {
  NavState site;
  double toolface_rad = 0.0;
  double t_s = 0.0;
  std::uint64_t seed = 3;

  void feed(HeadingHypotheses& bank, double spin, double seconds) {
    NavState turned = site;
    turned.q_nb = site.q_nb * Eigen::Quaterniond(Eigen::AngleAxisd(toolface_rad,
                                                                   Eigen::Vector3d::UnitZ()));
    StaticImu imu(turned, {}, testing::kRateHz, seed++, spin);
    const int epochs = static_cast<int>(std::lround(seconds * testing::kRateHz));
    for (int k = 0; k < epochs; ++k) {
      ImuIncrement increment = imu.next();
      increment.t_s += t_s;
      bank.step(increment);
    }
    toolface_rad += spin * seconds;
    t_s += seconds;
  }
};

// A still (or sliding) tool is not split on the mirror's account however long its heading
// interval reaches across the east-west line: its cross-axis biases and the Earth rate across
// its axis are one unknown on either side. Nor is a slide's orientation (half a turn) or rocking
// (back and forth). Once it rotates (a full turn, net, within 10 min), either way round or as
// slowly as 1 rpm, it is split into hypotheses 1.5 times narrower than it is then.
TEST(HeadingHypotheses, TheMirrorWaitsForTheToolToRotate) {
  NavState site = testing::static_truth_state();
  site.q_nb = quaternion_from_mwd(
      {.inclination_rad = 85.0 * kDeg, .toolface_rad = 0.0, .azimuth_rad = 89.0 * kDeg});
  const FilterOptions options = uncertain_heading_start(5.0 * kDeg);
  const auto still_minute = [&](TurningTool& tool) {
    auto bank = std::make_unique<HeadingHypotheses>(
        site, options, white_noise_plugins(site, 2), [&] { return white_noise_plugins(site, 2); });
    tool.feed(*bank, 0.0, 60.0);
    return bank;
  };
  const double pi = std::numbers::pi;
  {
    TurningTool tool{site};
    const auto bank = still_minute(tool);
    EXPECT_EQ(bank->splits(), 0u);
    EXPECT_EQ(bank->hypotheses(), 1u);
    // Still across the line, 1 deg away: +-3 sigma reaches well over it.
    EXPECT_GT(std::sqrt(bank->covariance()(kHeading, kHeading)), 2.0 * kDeg);
    tool.feed(*bank, pi / 10.0, 10.0);  // an orientation: half a turn in 10 s
    tool.feed(*bank, 0.0, 60.0);
    for (int k = 0; k < 6; ++k) {  // rocking: a quarter turn and back, six times
      tool.feed(*bank, pi / 10.0, 5.0);
      tool.feed(*bank, -pi / 10.0, 5.0);
    }
    EXPECT_EQ(bank->splits(), 0u) << "an orientation or rocking";
  }
  for (const double spin : {4.0 * pi, -4.0 * pi}) {  // 120 rpm
    TurningTool tool{site};
    const auto bank = still_minute(tool);
    const double sigma_still = std::sqrt(bank->covariance()(kHeading, kHeading));
    tool.feed(*bank, spin, 1.0);
    EXPECT_EQ(bank->splits(), 1u) << spin;
    ASSERT_GT(bank->hypotheses(), 1u) << spin;
    const double hypothesis_sigma =
        std::sqrt(bank->most_probable().covariance()(kHeading, kHeading));
    EXPECT_NEAR(hypothesis_sigma / sigma_still, 1.0 / 1.5, 0.05) << spin;
  }
  {
    TurningTool tool{site};
    const auto bank = still_minute(tool);
    tool.feed(*bank, 2.0 * pi / 60.0, 55.0);  // 1 rpm: 11/12 of a turn
    EXPECT_EQ(bank->splits(), 0u);
    tool.feed(*bank, 2.0 * pi / 60.0, 10.0);
    EXPECT_EQ(bank->splits(), 1u) << "1 rpm";
  }
}

// A running filter is checked at every epoch as a start is
// (FilterOptions::heading_hypotheses_split_running; here at every epoch, rotating or not, the
// ablation of ::heading_hypotheses_mirror_at_rotation, for the rule's geometry): a tool
// horizontal near east-west, still, started one plain filter at a heading sigma of 0.2 deg
// (below the mirror's quarter of a degree) whose heading uncertainty then grows (no aid; a gyro
// bias prior of 200 deg/h), becomes a bank of hypotheses 1.5 times narrower once its +-3 sigma
// headings reach the east-west line, 5 deg away (sigma 5/3 deg); the bank is that filter's
// distribution (the mixture's mean and covariance); without the rule it stays one filter.
TEST(HeadingHypotheses, ARunningFilterWhoseHeadingComesToNeedTheBankSplits) {
  NavState site = testing::static_truth_state();
  site.q_nb = quaternion_from_mwd(
      {.inclination_rad = 88.0 * kDeg, .toolface_rad = 0.0, .azimuth_rad = 85.0 * kDeg});
  FilterOptions options = uncertain_heading_start(0.2 * kDeg);
  options.heading_hypotheses_mirror_at_rotation = false;
  const double bias_sigma = 200.0 * kDeg / 3600.0;
  options.gyro_bias_sigma_radps.setConstant(bias_sigma);
  options.initial_core_covariance->diagonal().segment<3>(plugin::core_state::kGyroBias)
      .setConstant(bias_sigma * bias_sigma);
  (*options.initial_core_covariance)(kHeading, kGyroBiasX) =
      (*options.initial_core_covariance)(kGyroBiasX, kHeading) = 0.0;
  const auto plugins = [] {
    return NavigatorPlugins{
        std::make_shared<TestWhiteNoise>(plugin::SensorGroup::kGyro, 0.01 * kDeg / 60.0),
        std::make_shared<TestWhiteNoise>(plugin::SensorGroup::kAccel, 0.01 / 60.0),
        {}};
  };
  HeadingHypotheses bank(site, options, plugins(), plugins);
  FilterOptions one_filter = options;
  one_filter.heading_hypotheses_split_running = false;
  HeadingHypotheses plain(site, one_filter, plugins(), plugins);
  ASSERT_EQ(bank.hypotheses(), 1u);
  StaticImu imu(site, {.gyro_arw = 0.01 * kDeg / 60.0, .accel_vrw = 0.01 / 60.0}, 100.0, 9);
  int epochs = 0;
  for (; epochs < 20000 && bank.splits() == 0; ++epochs) {
    const ImuIncrement increment = imu.next();
    bank.step(increment);
    plain.step(increment);
  }
  ASSERT_EQ(bank.splits(), 1u) << "after " << epochs << " epochs";
  const Eigen::MatrixXd p = plain.covariance().topLeftCorner<15, 15>();
  EXPECT_NEAR(std::sqrt(p(kHeading, kHeading)), 5.0 / 3.0 * kDeg, 0.01 * kDeg);
  // +-3 sigma on a grid 2 sigma / 1.5 apart: seven hypotheses, the outer two below 1e-5 of the
  // middle one's prior weight; the mixture is the filter's distribution (the grid's
  // truncation loses a few % of the heading's variance).
  EXPECT_EQ(bank.hypotheses(), 5u);
  const Eigen::MatrixXd& mixture = bank.covariance();
  ASSERT_EQ(mixture.rows(), 15);
  EXPECT_NEAR(mixture(kHeading, kHeading) / p(kHeading, kHeading), 1.0, 0.05);
  for (int i = 0; i < 15; ++i) {
    if (i == kHeading) continue;
    EXPECT_NEAR(mixture(i, i) / p(i, i), 1.0, 0.05) << "state " << i;
  }
  EXPECT_LT(bank.state().q_nb.angularDistance(plain.state().q_nb), 1e-9);
  for (int k = 0; k < 1000; ++k) plain.step(imu.next());
  EXPECT_EQ(plain.hypotheses(), 1u);
  EXPECT_EQ(plain.splits(), 0u);
}

// A horizontal tool pointing east at 80 N, after a static alignment that measured the mean rate
// C_bn w_ie + b exactly (noise-free): the coarse (TRIAD) attitude, part of the bias that attitude
// implies, the heading sigma of a linearised fine alignment, the span's mean rate and the
// gyro-bias prior the alignment started from.
struct AlignedAt80N {
  NavState truth;
  NavState aligned;
  FilterOptions options;
};

AlignedAt80N aligned_at_80n(const Eigen::Vector3d& gyro_bias_radps, double prior_sigma_radps) {
  AlignedAt80N out;
  out.truth = testing::static_truth_state();
  out.truth.latitude_rad = 80.0 * kDeg;
  out.truth.q_nb = quaternion_from_mwd(
      {.inclination_rad = 90.0 * kDeg, .toolface_rad = 0.0, .azimuth_rad = 90.0 * kDeg});
  const Eigen::Vector3d earth_rate = earth_rate_n(out.truth.latitude_rad);
  const Eigen::Matrix3d c_bn = out.truth.q_nb.toRotationMatrix().transpose();
  StaticMeans means;
  means.omega_ib_b = c_bn * earth_rate + gyro_bias_radps;
  means.f_ib_b = -(c_bn * gravity_n(out.truth.latitude_rad, out.truth.height_m));
  means.duration_s = 600.0;
  out.aligned = out.truth;
  out.aligned.q_nb = coarse_alignment(means, out.truth.latitude_rad);
  out.options = uncertain_heading_start(18.0 * kDeg);
  // What the fine alignment hands over: the core bias it kept (here half the bias the coarse
  // attitude implies; the rest went to augmented states that do not reach the run).
  out.options.initial_gyro_bias_radps =
      0.5 * (means.omega_ib_b - out.aligned.q_nb.toRotationMatrix().transpose() * earth_rate);
  out.options.static_gyrocompass = FilterOptions::StaticGyrocompass{
      means.omega_ib_b, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(prior_sigma_radps)};
  return out;
}

// The hypothesis' heading error against the truth (rad, wrapped to (-pi, pi]).
double heading_error(const MwdNavigator& hypothesis, const NavState& truth) {
  const CoreEstimate estimate{hypothesis.state(), {}, {}};
  return core_difference(estimate, CoreEstimate{truth, {}, {}})(kHeading);
}

TEST(HeadingHypotheses, AfterAnAlignmentEveryHeadingExplainsTheMeasuredRate) {
  const double bias = 2.5 * kDeg / 3600.0;  // as large as the horizontal Earth rate at 80 N
  const AlignedAt80N start = aligned_at_80n(Eigen::Vector3d(0.2 * bias, -0.2 * bias, bias), bias);
  HeadingHypotheses bank(start.aligned, start.options, white_noise_plugins(start.aligned, 1),
                         [&] { return white_noise_plugins(start.aligned, 1); });
  // The along-hole bias turns the coarse heading 44 deg; the bank holds hypotheses near the
  // truth all the same.
  EXPECT_GT(std::abs(core_difference({start.aligned, {}, {}}, {start.truth, {}, {}})(kHeading)),
            30.0 * kDeg);
  ASSERT_GT(bank.hypotheses(), 10u);
  const Eigen::Vector3d earth_rate = earth_rate_n(start.truth.latitude_rad);
  const Eigen::Vector3d measured = start.options.static_gyrocompass->mean_rate_radps;
  double nearest = INFINITY;
  for (std::size_t i = 0; i < bank.hypotheses(); ++i) {
    const MwdNavigator& h = bank.hypothesis(i);
    const Eigen::Vector3d explained =
        h.gyro_bias_b() + h.state().q_nb.toRotationMatrix().transpose() * earth_rate;
    EXPECT_LT((explained - measured).norm(), 1e-15) << i;
    // Levelled as the alignment left it: only the heading differs.
    const MwdAttitude a = mwd_from_quaternion(h.state().q_nb);
    EXPECT_NEAR(a.inclination_rad, 90.0 * kDeg, 1e-9) << i;
    nearest = std::min(nearest, std::abs(heading_error(h, start.truth)));
  }
  EXPECT_LT(nearest, 4.0 * kDeg);  // half the grid spacing of 2 x 4 deg
}

TEST(HeadingHypotheses, TheAlignedBankIsTheGyrocompassPosteriorAndCoversTheTruth) {
  // Biases drawn from the prior the bank assumes, as large as the horizontal Earth rate
  // (2.6 deg/h at 80 N): the heading's posterior is far from Gaussian. Its probability of
  // lying below the truth (the PIT) must be uniform over the draws.
  const double sigma = 1.3 * kDeg / 3600.0;
  std::mt19937_64 engine(20261127);
  std::normal_distribution<double> normal(0.0, sigma);
  constexpr int kDraws = 300;
  int central_95 = 0, central_50 = 0;
  for (int draw = 0; draw < kDraws; ++draw) {
    const Eigen::Vector3d bias(normal(engine), normal(engine), normal(engine));
    const AlignedAt80N start = aligned_at_80n(bias, sigma);
    HeadingHypotheses bank(start.aligned, start.options, white_noise_plugins(start.aligned, 1),
                           [&] { return white_noise_plugins(start.aligned, 1); });
    double below = 0.0;
    for (std::size_t i = 0; i < bank.hypotheses(); ++i) {
      // Each hypothesis spreads its weight over its cell (4-deg sigma): the part below.
      const double error = heading_error(bank.hypothesis(i), start.truth);
      below += bank.weight(i) * 0.5 * std::erfc(error / (4.0 * kDeg * std::sqrt(2.0)));
    }
    central_95 += below > 0.025 && below < 0.975;
    central_50 += below > 0.25 && below < 0.75;
  }
  // Binomial 3-sigma bands for 300 draws: 95 % +- 3.8 %, 50 % +- 8.7 %.
  EXPECT_NEAR(central_95 / double(kDraws), 0.95, 0.038);
  EXPECT_NEAR(central_50 / double(kDraws), 0.50, 0.087);
}

// Stepped: the weights stay a distribution and the mixture covariance a covariance while the
// hypotheses are reweighed, dropped and merged (30 s at rest at 80 N, the bias the start
// implies in the truth).
TEST(HeadingHypotheses, SteppedTheMixtureStaysAProperDistribution) {
  const double bias = 1.0 * kDeg / 3600.0;
  const Eigen::Vector3d gyro_bias(0.2 * bias, -0.2 * bias, bias);
  const AlignedAt80N start = aligned_at_80n(gyro_bias, 1.3 * kDeg / 3600.0);
  HeadingHypotheses bank(start.aligned, start.options, white_noise_plugins(start.truth, 3),
                         [&] { return white_noise_plugins(start.truth, 3); });
  const std::size_t initial = bank.hypotheses();
  ASSERT_GT(initial, 5u);
  StaticImu imu(start.truth, {.gyro_arw = 0.01 * kDeg / 60.0, .accel_vrw = 0.01 / 60.0,
                              .gyro_bias = gyro_bias},
                100.0, 5);
  for (int k = 0; k < 3000; ++k) {
    bank.step(imu.next());
    if (k % 500 != 499) continue;
    double total = 0.0;
    for (std::size_t i = 0; i < bank.hypotheses(); ++i) total += bank.weight(i);
    EXPECT_NEAR(total, 1.0, 1e-12) << k;
    const Eigen::MatrixXd& p = bank.covariance();
    EXPECT_LT((p - p.transpose()).norm(), 1e-12 * p.norm()) << k;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(p.topLeftCorner(15, 15));
    EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-12 * eigen.eigenvalues().maxCoeff()) << k;
    EXPECT_TRUE(bank.state().q_nb.coeffs().allFinite()) << k;
  }
  EXPECT_LE(bank.hypotheses(), initial);
}

// A static aid (position 5 cm, velocity 2 mm/s, NIS gate 30 for its six components) whose
// noise at each 1-s epoch is drawn from that epoch's own seed, and which in [10 s, 20 s) either
// has no measurement (kDropout) or reads the velocity 0.1 m/s too high on every axis (kBurst: a
// burst of outliers every hypothesis gates out).
enum class Fault { kNone, kDropout, kBurst };

class FaultyStaticAid final : public plugin::AidPlugin {
 public:
  FaultyStaticAid(const NavState& site, Fault fault)
      : AidPlugin(plugin::NisGate{.enabled = true, .threshold = 30.0}), site_(site), fault_(fault) {}
  std::string_view type() const override { return "faulty_static"; }
  int measurement_size() const override { return 6; }
  bool has_measurement(double t_s) const override {
    return std::abs(t_s - std::round(t_s)) < 1e-6 && t_s > 0.5 &&
           !(fault_ == Fault::kDropout && in_fault(t_s));
  }
  bool measure(double t_s, const NavState& state, const plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    testing::time_seeded_static_measurement(site_, state, t_s, z, h, r);
    if (fault_ == Fault::kBurst && in_fault(t_s)) z.tail<3>().array() -= 0.1;
    return true;
  }
  std::string describe() const override { return "faulty_static"; }

 private:
  static bool in_fault(double t_s) { return t_s >= 10.0 && t_s < 20.0; }
  NavState site_;
  Fault fault_;
};

// The weights of a bank stepped 30 s at rest at 80 N (strict gate: no update is forced).
std::vector<double> weights_after_rest(Fault fault, bool robust) {
  const double bias = 1.0 * kDeg / 3600.0;
  const Eigen::Vector3d gyro_bias(0.2 * bias, -0.2 * bias, bias);
  AlignedAt80N start = aligned_at_80n(gyro_bias, 1.3 * kDeg / 3600.0);
  start.options.max_consecutive_rejections = 0;
  start.options.heading_hypotheses_robust_weights = robust;
  const auto plugins = [&] {
    return NavigatorPlugins{
        std::make_shared<TestWhiteNoise>(plugin::SensorGroup::kGyro, 0.01 * kDeg / 60.0),
        std::make_shared<TestWhiteNoise>(plugin::SensorGroup::kAccel, 0.01 / 60.0),
        {std::make_shared<FaultyStaticAid>(start.truth, fault)}};
  };
  HeadingHypotheses bank(start.aligned, start.options, plugins(), plugins);
  StaticImu imu(start.truth, {.gyro_arw = 0.01 * kDeg / 60.0, .accel_vrw = 0.01 / 60.0,
                              .gyro_bias = gyro_bias},
                100.0, 5);
  for (int k = 0; k < 3000; ++k) bank.step(imu.next());
  std::vector<double> weights;
  for (std::size_t i = 0; i < bank.hypotheses(); ++i) weights.push_back(bank.weight(i));
  return weights;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return 1.0;
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  return largest;
}

// Robust weights: a burst of outliers every hypothesis gates out says that the aid failed, not
// which heading is right; the bank ends as if the aid had been silent then. Read as Gaussian
// (the ablation), NIS in the thousands times differences of S between hypotheses move them.
TEST(HeadingHypotheses, AnOutlierBurstEveryHypothesisGatesOutDoesNotMoveTheWeights) {
  const std::vector<double> dropout = weights_after_rest(Fault::kDropout, true);
  ASSERT_GT(dropout.size(), 5u);
  EXPECT_LT(largest_difference(weights_after_rest(Fault::kBurst, true), dropout), 1e-6);
  EXPECT_GT(largest_difference(weights_after_rest(Fault::kBurst, false),
                               weights_after_rest(Fault::kDropout, false)),
            0.02);
}

// The consider rule is the bank's (FilterOptions::heading_hypotheses_hold_together): every
// hypothesis holds its heading while those near horizontal east-west carry at least half the
// weight, and estimates it otherwise. A horizontal hole pointing east at 80 N after an
// alignment: with a gyro-bias prior of 0.3 deg/h most of the weight lies near east-west, and
// every hypothesis holds its heading, those whose own attitude would estimate it too; with 1.3
// deg/h the weight spreads around the circle, and every hypothesis estimates its heading.
// Decided by each hypothesis' own attitude (the ablation), some hold and some estimate, and the
// weights compare held filters with estimated ones (docs/drilling-envelope.md, section 7).
TEST(HeadingHypotheses, TheBankHoldsEveryHypothesisHeadingAlike) {
  for (const double prior_deg_h : {0.3, 1.3}) {
    for (const bool together : {true, false}) {
      SCOPED_TRACE(std::to_string(prior_deg_h) + " deg/h, " +
                   (together ? "held together" : "each by its own attitude"));
      const double bias = prior_deg_h * kDeg / 3600.0;
      const Eigen::Vector3d gyro_bias(0.2 * bias, -0.2 * bias, bias);
      AlignedAt80N start = aligned_at_80n(gyro_bias, bias);
      start.options.heading_hypotheses_hold_together = together;
      const auto plugins = [&] {
        return NavigatorPlugins{
            std::make_shared<TestWhiteNoise>(plugin::SensorGroup::kGyro, 0.01 * kDeg / 60.0),
            std::make_shared<TestWhiteNoise>(plugin::SensorGroup::kAccel, 0.01 / 60.0),
            {std::make_shared<FaultyStaticAid>(start.truth, Fault::kNone)}};
      };
      HeadingHypotheses bank(start.aligned, start.options, plugins(), plugins);
      StaticImu imu(start.truth, {.gyro_arw = 0.01 * kDeg / 60.0, .accel_vrw = 0.01 / 60.0,
                                  .gyro_bias = gyro_bias},
                    100.0, 5);
      for (int k = 0; k < 500; ++k) bank.step(imu.next());  // aid epochs at 1, 2, ..., 5 s
      ASSERT_GE(bank.hypotheses(), 5u);
      double weight_near_east_west = 0.0;
      std::size_t held = 0;
      for (std::size_t i = 0; i < bank.hypotheses(); ++i) {
        const MwdNavigator& hypothesis = bank.hypothesis(i);
        if (heading_information_is_second_order(hypothesis.state().q_nb)) {
          weight_near_east_west += bank.weight(i);
        }
        held += hypothesis.heading_held();
      }
      const bool most_near_east_west = prior_deg_h < 1.0;
      if (most_near_east_west) {
        EXPECT_GT(weight_near_east_west, 0.6);
      } else {
        EXPECT_LT(weight_near_east_west, 0.4);
      }
      if (together) {
        EXPECT_EQ(held, most_near_east_west ? bank.hypotheses() : 0u);
      } else {
        EXPECT_GT(held, 0u);
        EXPECT_LT(held, bank.hypotheses());
      }
    }
  }
}

}  // namespace
}  // namespace stochnav

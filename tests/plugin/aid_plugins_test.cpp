// The bundled aid plugins loaded through the registry, each with aid data built here: the
// residual's sign and value (z = predicted - measured), H against the documented formula and a
// numerical derivative of the residual with respect to the error state, R positive definite and
// equal to its documented formula, and the epochs at which each aid measures.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "aid_test_support.hpp"
#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/plugin_registry.hpp"

namespace stochnav::plugin {
namespace {

namespace cs = core_state;
using aid_test::ErrorState;
using aid_test::perturbed;
using Map = Eigen::Matrix<double, 3, cs::kSize>;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

const PluginRegistry& registry() {
  static const PluginRegistry bundled({bundled_plugin_dir()});
  return bundled;
}

std::shared_ptr<AidPlugin> make_aid(std::string_view type, const nlohmann::json& params,
                                    const AidData& data, const NavState& initial = {},
                                    const std::string& pointer = "/aids/0/params") {
  const AidContext context{pointer, &data, initial, {}};
  return registry().create_aid(type, params, context, "/aids/0/plugin");
}

std::string config_error(const std::function<void()>& build) {
  try {
    build();
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(no error)";
}

struct Measurement {
  bool ok = false;
  Eigen::VectorXd z;
  Eigen::MatrixXd h;
  Eigen::MatrixXd r;
};

// Outputs start as NaN: an aid must write every entry.
Measurement measure(const AidPlugin& aid, double t_s, const NavState& state,
                    const ImuSample& imu = {}) {
  const int m = aid.measurement_size();
  Measurement out{false, Eigen::VectorXd::Constant(m, kNan),
                  Eigen::MatrixXd::Constant(m, cs::kSize, kNan),
                  Eigen::MatrixXd::Constant(m, m, kNan)};
  out.ok = aid.measure(t_s, state, imu, out.z, out.h, out.r);
  return out;
}

// H at (t, estimate) against d z / d dx. The estimate's interval mean moves with the error
// state through its map (InsInterval: mean_v_n(estimate) = mean_v_n(true) + map dx, noise left
// out); `estimate` plays the truth of the perturbations.
void expect_jacobian_is_the_derivative(const AidPlugin& aid, double t_s, const NavState& estimate,
                                       const ImuSample& imu = {}) {
  const Measurement at = measure(aid, t_s, estimate, imu);
  ASSERT_TRUE(at.ok);
  const auto residual = [&](const ErrorState& dx) {
    ImuSample moved = imu;
    moved.interval.mean_v_n += imu.interval.mean_velocity_error_map * dx;
    const Measurement m = measure(aid, t_s, perturbed(estimate, dx), moved);
    EXPECT_TRUE(m.ok);
    return Eigen::VectorXd(m.z);
  };
  const Eigen::MatrixXd numerical = aid_test::numerical_jacobian(residual, aid.measurement_size());
  EXPECT_LT((at.h - numerical).cwiseAbs().maxCoeff(), 1e-6) << aid.type() << " H\n"
                                                            << at.h << "\nnumerical\n"
                                                            << numerical;
}

void expect_positive_definite(const Eigen::MatrixXd& r) {
  ASSERT_TRUE(r.allFinite()) << r;
  EXPECT_LE((r - r.transpose()).cwiseAbs().maxCoeff(), 1e-18) << r;
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(r).eigenvalues().minCoeff(), 0.0) << r;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// A tool at 30 deg N, 100 deg E, 50 m, inclined and turned, moving slowly.
NavState drilling_state() {
  NavState state;
  state.latitude_rad = 30.0 * kRadPerDeg;
  state.longitude_rad = 100.0 * kRadPerDeg;
  state.height_m = 50.0;
  state.v_n = Eigen::Vector3d(0.01, -0.02, -0.03);
  state.q_nb = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
               Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitX()) *
               Eigen::AngleAxisd(-0.7, Eigen::Vector3d::UnitZ());
  return state;
}

// The two interval maps of the tests: [0, I, 0, 0, 0] (no drift within the interval), and the
// documented form [0, I, -(T/2) [f_n x], (T/2) C_nb, 0] for a constant specific force.
Map velocity_only_map() {
  Map map = Map::Zero();
  map.block<3, 3>(0, cs::kVelocity).setIdentity();
  return map;
}

Map drifting_map(const NavState& state, double duration_s) {
  Map map = velocity_only_map();
  const Eigen::Vector3d f_n(0.3, -0.2, 9.79);
  map.block<3, 3>(0, cs::kAttitude) = -0.5 * duration_s * skew(f_n);
  map.block<3, 3>(0, cs::kAccelBias) = 0.5 * duration_s * state.q_nb.toRotationMatrix();
  return map;
}

ImuSample interval_sample(double t_s, double duration_s, const Eigen::Vector3d& mean_v_n,
                          const Map& map) {
  ImuSample imu;
  imu.t_s = t_s;
  imu.interval.duration_s = duration_s;
  imu.interval.mean_v_n = mean_v_n;
  imu.interval.mean_velocity_error_map = map;
  Eigen::Matrix3d noise;
  noise << 4e-6, 1e-6, 0.0, 1e-6, 3e-6, -5e-7, 0.0, -5e-7, 2e-6;
  imu.interval.mean_velocity_noise_covariance = noise;
  return imu;
}

TEST(AidPlugins, AllAreBundled) {
  EXPECT_TRUE(registry().problems().empty());
  for (const char* type : {"static_position", "zupt", "rop", "pipe_length", "position_fix"}) {
    EXPECT_EQ(registry().find(PluginKind::kAid, type, "/aids/0/plugin").kind, PluginKind::kAid)
        << type;
  }
}

// --- zupt ---

TEST(ZuptAid, FlagsSourceMeasuresTheVelocityAtFlaggedRowsOnly) {
  const AidData data("aids.csv", {"t", "zupt"}, {{0.0, 1.0, 2.0, 3.0}, {0.0, 1.0, 1.0, 0.0}});
  const auto aid = make_aid("zupt", {{"sigma_velocity_mps", 0.002}}, data);
  ASSERT_EQ(aid->measurement_size(), 3);
  EXPECT_FALSE(aid->has_measurement(0.0));
  EXPECT_TRUE(aid->has_measurement(1.0));
  EXPECT_TRUE(aid->has_measurement(2.0));
  EXPECT_FALSE(aid->has_measurement(3.0));
  EXPECT_FALSE(aid->has_measurement(1.5));
  const NavState state = drilling_state();
  const Measurement m = measure(*aid, 1.0, state);
  ASSERT_TRUE(m.ok);
  EXPECT_EQ(Eigen::Vector3d(m.z), state.v_n);  // predicted v_n minus the measured zero
  EXPECT_EQ(m.r, Eigen::MatrixXd(4e-6 * Eigen::Matrix3d::Identity()));
  expect_positive_definite(m.r);
  expect_jacobian_is_the_derivative(*aid, 1.0, state);
}

TEST(ZuptAid, DetectorSourceMeasuresWhenTheSampleIsStationary) {
  const AidData no_data;
  NavState initial = drilling_state();
  initial.t_s = 10.0;
  const auto aid = make_aid("zupt", {{"source", "detector"}, {"rate_hz", 2.0}}, no_data, initial);
  EXPECT_TRUE(aid->has_measurement(10.5));
  EXPECT_TRUE(aid->has_measurement(11.0));
  EXPECT_FALSE(aid->has_measurement(10.25));
  const Eigen::Matrix3d c_bn = initial.q_nb.toRotationMatrix().transpose();
  ImuSample stationary;
  stationary.f_ib_b =
      c_bn * Eigen::Vector3d(0, 0, normal_gravity(initial.latitude_rad, initial.height_m));
  stationary.omega_ib_b = c_bn * earth_rate_n(initial.latitude_rad);
  const Measurement m = measure(*aid, 10.5, initial, stationary);
  ASSERT_TRUE(m.ok);
  EXPECT_EQ(Eigen::Vector3d(m.z), initial.v_n);
  expect_jacobian_is_the_derivative(*aid, 10.5, initial, stationary);
  ImuSample shaking = stationary;
  shaking.f_ib_b *= 1.02;  // | |f| - g | = 0.2 m/s^2 > 0.05
  EXPECT_FALSE(measure(*aid, 10.5, initial, shaking).ok);
  ImuSample turning = stationary;
  turning.omega_ib_b += Eigen::Vector3d(0.0, 0.0, 0.01);  // > 1e-3 rad/s
  EXPECT_FALSE(measure(*aid, 10.5, initial, turning).ok);
}

// --- rop ---

TEST(RopAid, ResidualIsTheMeanBodyVelocityMinusTheRopTrapezoid) {
  const AidData data("aids.csv", {"t", "rop_mph"}, {{0.0, 1.0, 3.0}, {36.0, 72.0, 108.0}});
  const auto aid = make_aid("rop", {}, data);
  ASSERT_EQ(aid->measurement_size(), 3);
  EXPECT_TRUE(aid->has_measurement(0.0));
  EXPECT_TRUE(aid->has_measurement(1.0));
  EXPECT_FALSE(aid->has_measurement(2.0));
  EXPECT_TRUE(aid->has_measurement(3.0));
  const NavState state = drilling_state();
  const Eigen::Vector3d mean_v_b(0.001, -0.002, 0.03);
  const Eigen::Vector3d mean_v_n = state.q_nb * mean_v_b;
  const auto z_at = [&](double t_s, double duration_s) {
    const Measurement m =
        measure(*aid, t_s, state, interval_sample(t_s, duration_s, mean_v_n, velocity_only_map()));
    EXPECT_TRUE(m.ok) << t_s;
    return Eigen::Vector3d(m.z);
  };
  // Row 0 at the interval's start: (36 + 72) / 2 m/h = 0.015 m/s.
  EXPECT_LT((z_at(1.0, 1.0) - Eigen::Vector3d(0.001, -0.002, 0.015)).norm(), 1e-12);
  // Row 1 at the start: (72 + 108) / 2 m/h = 0.025 m/s.
  EXPECT_LT((z_at(3.0, 2.0) - Eigen::Vector3d(0.001, -0.002, 0.005)).norm(), 1e-12);
  // The interval starts between rows: the row's own 108 m/h = 0.03 m/s.
  EXPECT_LT((z_at(3.0, 1.0) - Eigen::Vector3d(0.001, -0.002, 0.0)).norm(), 1e-12);
  for (double t_s : {0.0, 1.0}) {
    EXPECT_FALSE(
        measure(*aid, t_s, state, interval_sample(t_s, 0.0, mean_v_n, velocity_only_map())).ok);
  }
}

TEST(RopAid, JacobianAndCovarianceAreTheDocumentedFormulas) {
  const AidData data("aids.csv", {"t", "rop_mph"}, {{0.0, 2.0}, {50.0, 60.0}});
  const auto aid = make_aid(
      "rop", {{"sigma_rop_mps", 1e-3}, {"sigma_lateral_mps", 2e-4}, {"sigma_displacement_m", 0.01}},
      data);
  const NavState state = drilling_state();
  const Eigen::Matrix3d c_bn = state.q_nb.toRotationMatrix().transpose();
  const Eigen::Vector3d mean_v_n = state.q_nb * Eigen::Vector3d(0.002, 0.001, 0.02);
  // The attitude columns are taken about the reference velocity (ImuSample::reference_v_n),
  // which is not the INS's mean velocity; about the INS's they are the residual's derivative.
  const Eigen::Vector3d reference_v_n = state.q_nb * Eigen::Vector3d(0.0, 0.0, 0.0167);
  for (const Map& map : {velocity_only_map(), drifting_map(state, 2.0)}) {
    ImuSample imu = interval_sample(2.0, 2.0, mean_v_n, map);
    imu.reference_v_n = reference_v_n;
    const Measurement m = measure(*aid, 2.0, state, imu);
    ASSERT_TRUE(m.ok);
    Eigen::MatrixXd h = c_bn * map;
    h.block<3, 3>(0, cs::kAttitude) -= c_bn * skew(reference_v_n);
    EXPECT_LT((m.h - h).cwiseAbs().maxCoeff(), 1e-12) << m.h;
    imu.reference_v_n = mean_v_n;
    expect_jacobian_is_the_derivative(*aid, 2.0, state, imu);
    Eigen::Matrix3d r = c_bn * imu.interval.mean_velocity_noise_covariance * c_bn.transpose();
    r.diagonal() += Eigen::Vector3d(4e-8, 4e-8, 1e-6 + 2.0 * 0.005 * 0.005);  // sd / T = 0.005
    EXPECT_LT((m.r - r).cwiseAbs().maxCoeff(), 1e-18) << m.r;
    expect_positive_definite(m.r);
  }
}

// --- pipe_length ---

TEST(PipeLengthAid, MeasuresTheDepthIncrementOverTheIntervalFromThePreviousRow) {
  const AidData data("aids.csv", {"t", "measured_depth_m"},
                     {{0.0, 1.0, 2.0, 4.0}, {100.0, 100.02, 100.05, 100.09}});
  const auto aid = make_aid("pipe_length", {}, data);
  ASSERT_EQ(aid->measurement_size(), 1);
  for (double t_s : {0.0, 1.0, 2.0, 4.0}) EXPECT_TRUE(aid->has_measurement(t_s)) << t_s;
  EXPECT_FALSE(aid->has_measurement(3.0));
  EXPECT_FALSE(aid->has_measurement(1.5));
  const NavState state = drilling_state();
  const Eigen::Vector3d mean_v_n = state.q_nb * Eigen::Vector3d(0.001, -0.002, 0.035);
  const auto at = [&](double t_s, double duration_s) {
    return measure(*aid, t_s, state,
                   interval_sample(t_s, duration_s, mean_v_n, velocity_only_map()));
  };
  EXPECT_FALSE(at(0.0, 0.0).ok);  // the first row has no previous reading
  EXPECT_FALSE(at(0.0, 1.0).ok);
  const Measurement one_second = at(2.0, 1.0);  // 0.035 m/s along the axis, 0.03 m drilled
  ASSERT_TRUE(one_second.ok);
  EXPECT_NEAR(one_second.z(0), 0.005, 1e-12);
  const Measurement two_seconds = at(4.0, 2.0);  // 0.04 m over 2 s
  ASSERT_TRUE(two_seconds.ok);
  EXPECT_NEAR(two_seconds.z(0), 0.015, 1e-12);
  EXPECT_FALSE(at(2.0, 2.0).ok);  // the interval is not the row spacing
  EXPECT_FALSE(at(2.0, 0.5).ok);
  EXPECT_FALSE(at(4.0, 0.0).ok);
}

TEST(PipeLengthAid, JacobianAndCovarianceAreTheDocumentedFormulas) {
  const AidData data("aids.csv", {"t", "measured_depth_m"}, {{0.0, 2.0}, {100.0, 100.04}});
  const auto aid = make_aid(
      "pipe_length",
      {{"sigma_scale", 1e-3}, {"sigma_random_m", 0.05}, {"sigma_displacement_m", 0.01}}, data);
  const NavState state = drilling_state();
  const Eigen::Vector3d axis_n = state.q_nb * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d mean_v_n = state.q_nb * Eigen::Vector3d(0.002, 0.001, 0.02);
  // About a reference velocity along the axis the axis' own attitude term vanishes; about the
  // INS's mean velocity it is the residual's derivative.
  for (const Map& map : {velocity_only_map(), drifting_map(state, 2.0)}) {
    ImuSample imu = interval_sample(2.0, 2.0, mean_v_n, map);
    imu.reference_v_n = axis_n * 0.02;
    const Measurement m = measure(*aid, 2.0, state, imu);
    ASSERT_TRUE(m.ok);
    const Eigen::MatrixXd h = axis_n.transpose() * map;
    EXPECT_LT((m.h - h).cwiseAbs().maxCoeff(), 1e-12) << m.h;
    imu.reference_v_n = mean_v_n;
    expect_jacobian_is_the_derivative(*aid, 2.0, state, imu);
    const double scale_part = 1e-3 * 0.04;
    const double r = axis_n.dot(imu.interval.mean_velocity_noise_covariance * axis_n) +
                     (scale_part * scale_part + 2.0 * 0.05 * 0.05 + 2.0 * 0.01 * 0.01) / 4.0;
    EXPECT_NEAR(m.r(0, 0), r, 1e-15);
    expect_positive_definite(m.r);
  }
}

// Aids that state the tool's velocity (the navigator's reference trajectory).
TEST(AidPlugins, ZuptRopAndTallyStateTheVelocityTheyImply) {
  const NavState state = drilling_state();
  const Eigen::Vector3d axis_n = state.q_nb * Eigen::Vector3d::UnitZ();
  Eigen::Vector3d v_n;
  double sigma = 0.0;

  const AidData rop_data("aids.csv", {"t", "rop_mph"}, {{0.0, 1.0}, {36.0, 72.0}});
  const auto rop = make_aid("rop", {{"sigma_rop_mps", 1e-3}}, rop_data);
  EXPECT_TRUE(rop->states_velocity());
  ASSERT_TRUE(rop->stated_velocity_n(1.0, state, v_n, sigma));
  EXPECT_LT((v_n - axis_n * 0.02).norm(), 1e-15);  // 72 m/h along the axis
  EXPECT_EQ(sigma, 1e-3);
  EXPECT_FALSE(rop->stated_velocity_n(0.5, state, v_n, sigma));

  // The tally states its mean rate over the rows of the last 60 s, with that rate's sigma.
  std::vector<double> t, md;
  for (int k = 0; k <= 100; ++k) {
    t.push_back(k);
    md.push_back(100.0 + 0.01 * k);
  }
  const AidData tally_data("aids.csv", {"t", "measured_depth_m"}, {t, md});
  const auto tally =
      make_aid("pipe_length", {{"sigma_scale", 0.0}, {"sigma_random_m", 0.05}}, tally_data);
  EXPECT_TRUE(tally->states_velocity());
  ASSERT_TRUE(tally->stated_velocity_n(100.0, state, v_n, sigma));
  EXPECT_LT((v_n - axis_n * 0.01).norm(), 1e-12);
  EXPECT_NEAR(sigma, std::sqrt(2.0) * 0.05 / 60.0, 1e-15);
  ASSERT_TRUE(tally->stated_velocity_n(1.0, state, v_n, sigma));  // one row back only
  EXPECT_NEAR(sigma, std::sqrt(2.0) * 0.05, 1e-15);
  EXPECT_FALSE(tally->stated_velocity_n(0.0, state, v_n, sigma));

  const AidData zupt_data("aids.csv", {"t", "zupt"}, {{0.0, 1.0}, {1.0, 1.0}});
  const auto zupt = make_aid("zupt", {{"sigma_velocity_mps", 2e-3}}, zupt_data);
  EXPECT_TRUE(zupt->states_velocity());
  v_n.setConstant(1.0);
  ASSERT_TRUE(zupt->stated_velocity_n(1.0, state, v_n, sigma));
  EXPECT_EQ(v_n, Eigen::Vector3d::Zero());
  EXPECT_EQ(sigma, 2e-3);
}

// --- static_position ---

NavState site() {
  NavState state;
  state.latitude_rad = 30.0 * kRadPerDeg;
  state.longitude_rad = 100.0 * kRadPerDeg;
  state.height_m = 50.0;
  return state;
}

const nlohmann::json kSiteParams = {
    {"latitude_deg", 30.0}, {"longitude_deg", 100.0}, {"height_m", 50.0}};

ErrorState offset(const Eigen::Vector3d& dr_m,
                  const Eigen::Vector3d& dv_mps = Eigen::Vector3d::Zero()) {
  ErrorState dx = ErrorState::Zero();
  dx.segment<3>(cs::kPosition) = dr_m;
  dx.segment<3>(cs::kVelocity) = dv_mps;
  return dx;
}

TEST(StaticPositionAid, MeasuresThePositionErrorAgainstTheSiteAndTheVelocity) {
  const AidData no_data;
  NavState initial = drilling_state();  // elsewhere: the site param wins
  initial.t_s = 10.0;
  const auto aid = make_aid("static_position",
                            {{"site", kSiteParams},
                             {"rate_hz", 2.0},
                             {"sigma_position_m", 0.02},
                             {"sigma_velocity_mps", 0.003}},
                            no_data, initial);
  ASSERT_EQ(aid->measurement_size(), 6);
  EXPECT_FALSE(aid->has_measurement(10.0));
  EXPECT_TRUE(aid->has_measurement(10.5));
  EXPECT_TRUE(aid->has_measurement(11.0));
  EXPECT_FALSE(aid->has_measurement(10.25));
  EXPECT_NEAR(aid->gate().threshold, 22.458, 1e-3);  // chi2(6) at 99.9 %
  const NavState estimate =
      perturbed(site(), offset({2.0, 1.0, -3.0}, {0.1, 0.2, 0.3}));  // 2 m E, 1 m N, 3 m down
  const Measurement m = measure(*aid, 10.5, estimate);
  ASSERT_TRUE(m.ok);
  Eigen::VectorXd z(6);
  z << 2.0, 1.0, -3.0, 0.1, 0.2, 0.3;
  EXPECT_LT((m.z - z).cwiseAbs().maxCoeff(), 1e-6) << m.z;
  Eigen::VectorXd variances(6);
  variances << 4e-4, 4e-4, 4e-4, 9e-6, 9e-6, 9e-6;
  EXPECT_EQ(m.r, Eigen::MatrixXd(variances.asDiagonal()));
  expect_positive_definite(m.r);
  expect_jacobian_is_the_derivative(*aid, 10.5, estimate);
}

TEST(StaticPositionAid, WithoutZeroVelocityMeasuresThePositionOnly) {
  const AidData no_data;
  const auto aid =
      make_aid("static_position", {{"site", kSiteParams}, {"zero_velocity", false}}, no_data);
  ASSERT_EQ(aid->measurement_size(), 3);
  EXPECT_NEAR(aid->gate().threshold, 16.266, 1e-3);  // chi2(3) at 99.9 %
  const NavState estimate = perturbed(site(), offset({2.0, 1.0, -3.0}, {0.1, 0.2, 0.3}));
  const Measurement m = measure(*aid, 1.0, estimate);
  ASSERT_TRUE(m.ok);
  EXPECT_LT((m.z - Eigen::Vector3d(2.0, 1.0, -3.0)).cwiseAbs().maxCoeff(), 1e-6) << m.z;
  EXPECT_EQ(m.r, Eigen::MatrixXd(1e-4 * Eigen::Matrix3d::Identity()));
  expect_jacobian_is_the_derivative(*aid, 1.0, estimate);
  EXPECT_NE(config_error([&] {
              make_aid("static_position", {{"zero_velocity", 1}}, no_data);
            }).find("/aids/0/params/zero_velocity"),
            std::string::npos);
}

TEST(StaticPositionAid, SiteDefaultsToTheInitialPosition) {
  const AidData no_data;
  const NavState initial = drilling_state();
  const auto aid = make_aid("static_position", {}, no_data, initial);
  const Measurement m = measure(*aid, 1.0, initial);
  ASSERT_TRUE(m.ok);
  EXPECT_LT(m.z.head<3>().norm(), 1e-9);
  EXPECT_EQ(Eigen::Vector3d(m.z.tail<3>()), initial.v_n);
}

// --- position_fix ---

// Rows 0 and 3 carry a fix; rows 1 and 2 have a sigma <= 0. Row 3 sits by the antimeridian.
AidData fix_data() {
  return AidData("aids.csv",
                 {"t", "fix_latitude_deg", "fix_longitude_deg", "fix_height_m", "fix_sigma_east_m",
                  "fix_sigma_north_m", "fix_sigma_up_m"},
                 {{0.0, 1.0, 2.0, 3.0},
                  {30.0, 30.0, 30.0, -45.0},
                  {100.0, 100.0, 100.0, 180.0 - 1e-6},
                  {50.0, 50.0, 50.0, -20.0},
                  {1.0, 0.0, 1.0, 0.5},
                  {2.0, 1.0, -1.0, 0.5},
                  {3.0, 1.0, 1.0, 0.5}});
}

TEST(PositionFixAid, ResidualIsTheEnuOffsetOfTheEstimateFromTheFix) {
  const AidData data = fix_data();
  const auto aid = make_aid("position_fix", {}, data);
  ASSERT_EQ(aid->measurement_size(), 3);
  // 1 m north, 2 m east, 3 m below the fix.
  const NavState estimate = perturbed(site(), offset({2.0, 1.0, -3.0}, {0.1, 0.2, 0.3}));
  const Measurement m = measure(*aid, 0.0, estimate);
  ASSERT_TRUE(m.ok);
  EXPECT_LT((m.z - Eigen::Vector3d(2.0, 1.0, -3.0)).cwiseAbs().maxCoeff(), 1e-6) << m.z;
  EXPECT_EQ(m.r, Eigen::MatrixXd(Eigen::Vector3d(1.0, 4.0, 9.0).asDiagonal()));
  expect_positive_definite(m.r);
  expect_jacobian_is_the_derivative(*aid, 0.0, estimate);
  expect_jacobian_is_the_derivative(*aid, 0.0, drilling_state());
}

TEST(PositionFixAid, EastOffsetWrapsAcrossTheAntimeridian) {
  const AidData data = fix_data();
  const auto aid = make_aid("position_fix", {}, data);
  NavState fix;
  fix.latitude_rad = -45.0 * kRadPerDeg;
  fix.longitude_rad = (180.0 - 1e-6) * kRadPerDeg;
  fix.height_m = -20.0;
  NavState estimate = perturbed(fix, offset({5.0, 0.0, 0.0}));
  ASSERT_GT(estimate.longitude_rad, std::numbers::pi);
  estimate.longitude_rad -= 2.0 * std::numbers::pi;  // written as a west longitude
  const Measurement m = measure(*aid, 3.0, estimate);
  ASSERT_TRUE(m.ok);
  EXPECT_LT((m.z - Eigen::Vector3d(5.0, 0.0, 0.0)).cwiseAbs().maxCoeff(), 1e-6) << m.z;
  EXPECT_EQ(m.r, Eigen::MatrixXd(0.25 * Eigen::Matrix3d::Identity()));
}

TEST(PositionFixAid, RowsWithANonPositiveSigmaCarryNoFix) {
  const AidData data = fix_data();
  const auto aid = make_aid("position_fix", {}, data);
  EXPECT_TRUE(aid->has_measurement(0.0));
  EXPECT_FALSE(aid->has_measurement(1.0));
  EXPECT_FALSE(aid->has_measurement(2.0));
  EXPECT_TRUE(aid->has_measurement(3.0));
  EXPECT_FALSE(aid->has_measurement(0.5));
  EXPECT_FALSE(measure(*aid, 1.0, site()).ok);
  EXPECT_FALSE(measure(*aid, 2.0, site()).ok);
  EXPECT_NE(aid->describe().find("2 position fixes"), std::string::npos) << aid->describe();
}

TEST(PositionFixAid, ColumnsCanBeRenamed) {
  const AidData data("survey.csv", {"t", "lat", "lon", "fix_height_m", "se", "sn", "su"},
                     {{5.0}, {30.0}, {100.0}, {50.0}, {0.1}, {0.2}, {0.3}});
  const nlohmann::json columns = {{"latitude_deg", "lat"},
                                  {"longitude_deg", "lon"},
                                  {"sigma_east_m", "se"},
                                  {"sigma_north_m", "sn"},
                                  {"sigma_up_m", "su"}};  // height keeps its default name
  const auto aid = make_aid("position_fix", {{"columns", columns}}, data);
  EXPECT_TRUE(aid->has_measurement(5.0));
  const Measurement m = measure(*aid, 5.0, perturbed(site(), offset({2.0, 1.0, -3.0})));
  ASSERT_TRUE(m.ok);
  EXPECT_LT((m.z - Eigen::Vector3d(2.0, 1.0, -3.0)).cwiseAbs().maxCoeff(), 1e-6) << m.z;
  EXPECT_LT((m.r.diagonal() - Eigen::Vector3d(0.01, 0.04, 0.09)).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(PositionFixAid, BadParamsAndMissingColumnsNameTheirPointer) {
  const AidData data = fix_data();
  const auto error = [&](const nlohmann::json& params, const AidData& aid_data) {
    return config_error(
        [&] { make_aid("position_fix", params, aid_data, NavState{}, "/aids/2/params"); });
  };
  const struct {
    nlohmann::json params;
    std::string message;
  } cases[] = {
      {{{"colums", {}}}, "/aids/2/params/colums: unknown key"},
      {{{"columns", {{"lat", "x"}}}}, "/aids/2/params/columns/lat: unknown key"},
      {{{"columns", {{"height_m", 3}}}},
       "/aids/2/params/columns/height_m: found 3; expected a non-empty string"},
      {{{"columns", {{"sigma_up_m", "su2"}}}},
       "/aids/2/params/columns/sigma_up_m: aid data aids.csv has no column 'su2'"},
  };
  for (const auto& c : cases) {
    const std::string message = error(c.params, data);
    EXPECT_NE(message.find(c.message), std::string::npos) << message;
  }
  const AidData no_height("aids.csv", {"t", "fix_latitude_deg", "fix_longitude_deg"},
                          {{0.0}, {30.0}, {100.0}});
  const std::string message = error({}, no_height);
  EXPECT_NE(message.find("/aids/2/params/columns/height_m: aid data aids.csv has no column "
                         "'fix_height_m'"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace stochnav::plugin

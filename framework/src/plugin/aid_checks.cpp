#include "stochnav/plugin/aid_checks.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "stochnav/filter/core_correction.hpp"
#include "stochnav/ins/cross_product_matrix.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav::plugin {
namespace {

namespace cs = core_state;
constexpr double kUnwritten = std::numeric_limits<double>::quiet_NaN();
/// Written around the outputs: an aid that writes beside them changes it.
constexpr double kGuard = -1.2345e300;

const char* const kCoreStateNames[cs::kSize] = {
    "dr_east", "dr_north", "dr_up", "dv_east", "dv_north", "dv_up", "phi_east", "phi_north",
    "phi_up",  "b_a_x",    "b_a_y", "b_a_z",   "b_g_x",    "b_g_y", "b_g_z"};

/// One call of measure() with NaN outputs inside a guard row and column.
struct AidMeasurement {
  bool ok = false;
  Eigen::VectorXd z;
  Eigen::MatrixXd h;
  Eigen::MatrixXd r;
  bool wrote_outside = false;  ///< changed an entry beside its outputs
};

AidMeasurement measure_aid(const AidPlugin& aid, double t_s, const NavState& state,
                           const ImuSample& imu) {
  const int m = aid.measurement_size();
  Eigen::VectorXd z_buffer = Eigen::VectorXd::Constant(m + 1, kGuard);
  Eigen::MatrixXd h_buffer = Eigen::MatrixXd::Constant(m + 1, cs::kSize + 1, kGuard);
  Eigen::MatrixXd r_buffer = Eigen::MatrixXd::Constant(m + 1, m + 1, kGuard);
  z_buffer.head(m).setConstant(kUnwritten);
  h_buffer.topLeftCorner(m, cs::kSize).setConstant(kUnwritten);
  r_buffer.topLeftCorner(m, m).setConstant(kUnwritten);
  AidMeasurement out;
  // The blocks of the buffers reach measure() through Eigen::Ref, as the navigator's do.
  out.ok = aid.measure(t_s, state, imu, z_buffer.head(m), h_buffer.topLeftCorner(m, cs::kSize),
                       r_buffer.topLeftCorner(m, m));
  out.z = z_buffer.head(m);
  out.h = h_buffer.topLeftCorner(m, cs::kSize);
  out.r = r_buffer.topLeftCorner(m, m);
  out.wrote_outside = z_buffer(m) != kGuard || (h_buffer.row(m).array() != kGuard).any() ||
                      (h_buffer.col(cs::kSize).array() != kGuard).any() ||
                      (r_buffer.row(m).array() != kGuard).any() ||
                      (r_buffer.col(m).array() != kGuard).any();
  return out;
}

double max_abs_entry(const Eigen::MatrixXd& a) {
  return a.size() == 0 ? 0.0 : a.cwiseAbs().maxCoeff();
}

/// The estimate and the IMU sample the aid sees when the error state is dx = estimate - truth.
struct PerturbedEpoch {
  NavState state;
  ImuSample imu;
};

PerturbedEpoch with_error(const AidCheckCase& at, const Eigen::Matrix<double, cs::kSize, 1>& dx) {
  // The navigator feeds a correction x back as estimate -> truth; -dx takes the truth to the
  // estimate that errs by dx, through the same formulas.
  CoreEstimate estimate{at.truth, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const Eigen::VectorXd correction = -dx;
  apply_core_correction(correction, estimate);
  PerturbedEpoch epoch{estimate.state, at.imu};
  epoch.imu.f_ib_b -= dx.segment<3>(cs::kAccelBias);
  epoch.imu.omega_ib_b -= dx.segment<3>(cs::kGyroBias);
  epoch.imu.interval.mean_v_n += at.imu.interval.mean_velocity_error_map * dx;
  return epoch;
}

std::string vector_text(const Eigen::VectorXd& v) {
  std::string text = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) text += fmt::format("{}{:.6g}", i ? ", " : "", v(i));
  return text + "]";
}

bool same_outputs(const AidMeasurement& a, const AidMeasurement& b) {
  const auto same = [](const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
    return x.rows() == y.rows() && x.cols() == y.cols() &&
           ((x.array() == y.array()) || (x.array().isNaN() && y.array().isNaN())).all();
  };
  return a.ok == b.ok && same(a.z, b.z) && same(a.h, b.h) && same(a.r, b.r);
}

}  // namespace

ImuSample steady_imu_sample(const NavState& truth, double t_s, double interval_s) {
  const Eigen::Matrix3d c_nb = truth.q_nb.toRotationMatrix();
  const Eigen::Vector3d f_n = -gravity_n(truth.latitude_rad, truth.height_m);
  ImuSample imu;
  imu.t_s = t_s;
  imu.f_ib_b = c_nb.transpose() * f_n;
  imu.omega_ib_b = c_nb.transpose() * earth_rate_n(truth.latitude_rad);
  imu.reference_v_n = truth.v_n;
  if (interval_s > 0.0) {
    InsInterval& interval = imu.interval;
    interval.duration_s = interval_s;
    interval.mean_v_n = truth.v_n;
    interval.mean_velocity_error_map.block<3, 3>(0, cs::kVelocity).setIdentity();
    interval.mean_velocity_error_map.block<3, 3>(0, cs::kAttitude) = -0.5 * interval_s * skew(f_n);
    interval.mean_velocity_error_map.block<3, 3>(0, cs::kAccelBias) = 0.5 * interval_s * c_nb;
    interval.mean_velocity_noise_covariance = 1e-8 * Eigen::Matrix3d::Identity();
  }
  return imu;
}

std::string AidCheckOptions::invalid_reason() const {
  if (!(position_step_m > 0.0)) return "position_step_m <= 0";
  if (!(step > 0.0)) return "step <= 0";
  if (!(jacobian_absolute >= 0.0) || !(jacobian_relative >= 0.0)) {
    return "a jacobian tolerance is negative";
  }
  if (!(residual_tolerance >= 0.0)) return "residual_tolerance < 0";
  if (!(symmetry_tolerance >= 0.0)) return "symmetry_tolerance < 0";
  return "";
}

std::vector<std::string> check_aid_sizes(const AidPlugin& aid, const AidCheckCase& at) {
  std::vector<std::string> failures;
  const int m = aid.measurement_size();
  if (m < 1) return {fmt::format("sizes: measurement_size() = {}; expected >= 1", m)};
  if (aid.measurement_size() != m) {
    failures.push_back(
        fmt::format("sizes: measurement_size() changed from {} to {}", m, aid.measurement_size()));
  }
  const bool due = aid.has_measurement(at.t_s);
  if (!due) {
    failures.push_back(fmt::format(
        "sizes: has_measurement({} s) is false; check at a time of the aid data with a measurement",
        at.t_s));
    return failures;
  }
  if (!aid.has_measurement(at.t_s)) {
    failures.push_back(fmt::format("sizes: has_measurement({} s) changed between calls", at.t_s));
  }
  const AidMeasurement first = measure_aid(aid, at.t_s, at.truth, at.imu);
  if (!first.ok) {
    failures.push_back(fmt::format(
        "sizes: measure() at t = {} s returned false though has_measurement is true (for an "
        "interval aid: does the interval of {} s match the aid data?)",
        at.t_s, at.imu.interval.duration_s));
    return failures;
  }
  if (first.wrote_outside) {
    failures.push_back("sizes: measure() wrote beside its outputs (z m, H m x 15, R m x m)");
  }
  const auto unwritten = [&](const Eigen::MatrixXd& a, const char* name) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      for (Eigen::Index j = 0; j < a.cols(); ++j) {
        if (!std::isfinite(a(i, j))) {
          const std::string column =
              (a.cols() == cs::kSize) ? std::string(" (") + kCoreStateNames[j] + ")" : "";
          failures.push_back(fmt::format("sizes: {}({}, {}){} not written or not finite ({})", name,
                                         i, j, column, a(i, j)));
          return;
        }
      }
    }
  };
  unwritten(first.z, "z");
  unwritten(first.h, "H");
  unwritten(first.r, "R");
  if (!same_outputs(first, measure_aid(aid, at.t_s, at.truth, at.imu))) {
    failures.push_back("sizes: a second measure() with the same inputs gave other outputs");
  }
  return failures;
}

std::vector<std::string> check_aid_covariance(const AidPlugin& aid, const AidCheckCase& at,
                                              const AidCheckOptions& options) {
  const AidMeasurement m = measure_aid(aid, at.t_s, at.truth, at.imu);
  if (!m.ok) return {};
  if (!m.r.allFinite()) return {"covariance: R is not finite"};
  const double scale = max_abs_entry(m.r);
  const double asymmetry = max_abs_entry(m.r - m.r.transpose());
  if (asymmetry > options.symmetry_tolerance * scale) {
    return {fmt::format("covariance: R not symmetric (max |R - R^T| = {:.3g}, max |R| = {:.3g})",
                        asymmetry, scale)};
  }
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m.r, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(eigenvalues.minCoeff() > 0.0)) {
    return {
        fmt::format("covariance: R not positive definite (smallest eigenvalue {:.3g}, "
                    "max |R| = {:.3g})",
                    eigenvalues.minCoeff(), scale)};
  }
  return {};
}

std::vector<std::string> check_aid_residual_at_truth(const AidPlugin& aid, const AidCheckCase& at,
                                                     const AidCheckOptions& options) {
  const AidMeasurement m = measure_aid(aid, at.t_s, at.truth, at.imu);
  if (!m.ok) return {};
  std::vector<std::string> failures;
  for (Eigen::Index i = 0; i < m.z.size(); ++i) {
    const double sigma = std::sqrt(std::max(m.r(i, i), 0.0));
    if (!(std::abs(m.z(i)) <= options.residual_tolerance * sigma)) {
      failures.push_back(fmt::format(
          "truth: z({}) = {:.6g} at the true state, {:.3g} sigma (tolerance {:.3g} sigma, "
          "sigma = {:.3g}); the aid data must be what the tool at the true state measures, or "
          "the residual is not h(x) - y",
          i, m.z(i), sigma > 0.0 ? m.z(i) / sigma : std::numeric_limits<double>::infinity(),
          options.residual_tolerance, sigma));
    }
  }
  return failures;
}

std::vector<std::string> check_aid_jacobian(const AidPlugin& aid, const AidCheckCase& at,
                                            const AidCheckOptions& options) {
  const AidMeasurement base = measure_aid(aid, at.t_s, at.truth, at.imu);
  if (!base.ok) return {};
  std::vector<std::string> failures;
  for (int j = 0; j < cs::kSize; ++j) {
    const double step = j < cs::kVelocity ? options.position_step_m : options.step;
    Eigen::Matrix<double, cs::kSize, 1> dx = Eigen::Matrix<double, cs::kSize, 1>::Zero();
    dx(j) = step;
    const PerturbedEpoch plus = with_error(at, dx);
    const PerturbedEpoch minus = with_error(at, -dx);
    const AidMeasurement up = measure_aid(aid, at.t_s, plus.state, plus.imu);
    const AidMeasurement down = measure_aid(aid, at.t_s, minus.state, minus.imu);
    if (!up.ok || !down.ok) {
      failures.push_back(
          fmt::format("jacobian: column {} ({}): measure() returned false at an error of {:.3g}", j,
                      kCoreStateNames[j], step));
      continue;
    }
    const Eigen::VectorXd numerical = (up.z - down.z) / (2.0 * step);
    for (Eigen::Index i = 0; i < numerical.size(); ++i) {
      const double analytic = base.h(i, j);
      const double allowed =
          options.jacobian_absolute +
          options.jacobian_relative * std::max(std::abs(analytic), std::abs(numerical(i)));
      if (!(std::abs(analytic - numerical(i)) <= allowed)) {
        failures.push_back(fmt::format(
            "jacobian: H({}, {}) ({}) = {:.6g}, finite difference {:.6g} (difference {:.3g} > "
            "{:.3g})",
            i, j, kCoreStateNames[j], analytic, numerical(i), analytic - numerical(i), allowed));
      }
    }
  }
  return failures;
}

std::vector<std::string> check_aid_round_trip(const AidPlugin& aid, const AidRebuild& rebuild,
                                              const nlohmann::json& params,
                                              const AidCheckCase& at) {
  std::vector<std::string> failures;
  const std::string described = aid.describe();
  if (described.rfind(std::string(aid.type()), 0) != 0) {
    failures.push_back("round trip: describe() \"" + described +
                       "\" does not start with the type '" + std::string(aid.type()) + "'");
  }
  std::shared_ptr<AidPlugin> again;
  try {
    again = rebuild(params);
  } catch (const std::exception& error) {
    failures.push_back(std::string("round trip: the factory failed on the same params: ") +
                       error.what());
    return failures;
  }
  if (again == nullptr) {
    failures.push_back("round trip: the factory returned no aid");
    return failures;
  }
  if (again->type() != aid.type() || again->measurement_size() != aid.measurement_size() ||
      again->describe() != described) {
    failures.push_back("round trip: the aid rebuilt from the same params differs: \"" +
                       again->describe() + "\" (size " + std::to_string(again->measurement_size()) +
                       ") against \"" + described + "\" (size " +
                       std::to_string(aid.measurement_size()) + ")");
    return failures;
  }
  if (aid.measurement_size() < 1 || !aid.has_measurement(at.t_s)) return failures;
  const AidMeasurement a = measure_aid(aid, at.t_s, at.truth, at.imu);
  const AidMeasurement b = measure_aid(*again, at.t_s, at.truth, at.imu);
  if (!same_outputs(a, b)) {
    failures.push_back(fmt::format(
        "round trip: the aid rebuilt from the same params measures otherwise at t = {} s: z = {} "
        "against {}",
        at.t_s, vector_text(b.z), vector_text(a.z)));
  }
  return failures;
}

std::vector<std::string> check_aid(const AidPlugin& aid, const AidRebuild& rebuild,
                                   const nlohmann::json& params, const AidCheckCase& at,
                                   const AidCheckOptions& options) {
  if (const std::string reason = options.invalid_reason(); !reason.empty()) {
    return {"options: " + reason};
  }
  std::vector<std::string> failures = check_aid_sizes(aid, at);
  const auto append = [&](std::vector<std::string> more) {
    failures.insert(failures.end(), more.begin(), more.end());
  };
  if (aid.measurement_size() >= 1 && aid.has_measurement(at.t_s)) {
    append(check_aid_covariance(aid, at, options));
    append(check_aid_residual_at_truth(aid, at, options));
    append(check_aid_jacobian(aid, at, options));
  }
  append(check_aid_round_trip(aid, rebuild, params, at));
  return failures;
}

}  // namespace stochnav::plugin

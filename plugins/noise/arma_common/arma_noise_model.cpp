#include "arma_noise_model.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/model/reporting_units.hpp"
#include "stochnav/plugin/tabulated_noise_model.hpp"

namespace stochnav::plugin::arma_noise {
namespace {

constexpr const char* kAxisNames[] = {"x", "y", "z"};

const ParamUnit kRateUnit = ParamUnit::of(ParameterDimension::kRate);

// One axis of each kind: {"ar": [...], "sigma": s} and {"ar": [...], "ma": [...], "sigma": s}.
const ParamTable<ArmaModel> kArAxisTable{
    series(&ArmaModel::ar, "ar", ParamUnit::fixed(""), {.min_size = 1}, "AR coefficients phi_i"),
    scalar(&ArmaModel::sigma, "sigma", kRateUnit, Bound::kPositive, kRequired,
           "innovation standard deviation of the block mean"),
};
const ParamTable<ArmaModel> kArmaAxisTable{
    series(&ArmaModel::ar, "ar", ParamUnit::fixed(""), {.min_size = 0, .required = false},
           "AR coefficients phi_i"),
    series(&ArmaModel::ma, "ma", ParamUnit::fixed(""), {.min_size = 0, .required = false},
           "MA coefficients theta_i"),
    scalar(&ArmaModel::sigma, "sigma", kRateUnit, Bound::kPositive, kRequired,
           "innovation standard deviation of the block mean"),
};

/// ConfigError when an axis' AR part is not stationary or it needs too many states.
void check_axes(const ArmaNoiseParams& params, const std::string& axes_pointer) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const ArmaModel& model = params.axes[axis];
    const std::string pointer = axes_pointer + "/" + std::to_string(axis);
    if (!is_stationary(model.ar)) {
      throw ConfigError(pointer + "/ar: found " + nlohmann::json(model.ar).dump() +
                        "; expected a stationary AR part (all roots of 1 - sum phi_i z^i outside "
                        "the unit circle)");
    }
    const int r = static_cast<int>(std::max(model.ar.size(), model.ma.size() + 1));
    if (r > kMaxArmaStateSize) {
      throw ConfigError(pointer + ": found max(p, q + 1) = " + std::to_string(r) +
                        " states; expected at most " + std::to_string(kMaxArmaStateSize));
    }
  }
}

class ArmaNoise final : public TabulatedNoiseModel<ArmaNoiseParams> {
 public:
  ArmaNoise(Kind kind, SensorGroup group, const ArmaNoiseParams& params)
      : TabulatedNoiseModel(group, model_table(kind), params), kind_(kind) {
    for (int axis = 0; axis < 3; ++axis) {
      spaces_[axis] = state_space(params.axes[axis]);
      offsets_[axis] = size_;
      size_ += spaces_[axis].size();
    }
    initial_ = Eigen::MatrixXd::Zero(size_, size_);
    for (int axis = 0; axis < 3; ++axis) {
      const int r = spaces_[axis].size();
      initial_.block(offsets_[axis], offsets_[axis], r, r) = stationary_covariance(spaces_[axis]);
    }
    cached_phi_ = Eigen::MatrixXd::Identity(size_, size_);
    cached_q_ = Eigen::MatrixXd::Zero(size_, size_);
  }

  std::string_view type() const override { return type_name(kind_); }
  int augmented_size() const override { return size_; }

  void white_noise_covariance(double, double, Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    q_white.setZero();
  }

  void bias_walk_covariance(double, double dt_s,
                            Eigen::Ref<Eigen::MatrixXd> q_bias) const override {
    q_bias.setZero();
    for (int i = 0; i < 3; ++i) q_bias(i, i) = parameters().k[i] * parameters().k[i] * dt_s;
  }

  void augmented_transition(double, double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                            Eigen::Ref<Eigen::MatrixXd> q_d) const override {
    const long steps = std::lround(dt_s / parameters().interval_s);
    // One cached result per distinct block count (the filter mostly steps one interval).
    if (steps != cached_steps_) {
      for (int axis = 0; axis < 3; ++axis) {
        const int r = spaces_[axis].size(), offset = offsets_[axis];
        k_step_transition(spaces_[axis], static_cast<int>(steps),
                          cached_phi_.block(offset, offset, r, r),
                          cached_q_.block(offset, offset, r, r));
      }
      cached_steps_ = steps;
    }
    phi = cached_phi_;
    q_d = cached_q_;
  }

  void augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const override {
    p0 = initial_;
  }

  void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const override {
    map.setZero();
    for (int axis = 0; axis < 3; ++axis) map(axis, offsets_[axis]) = 1.0;
  }

  // The table's description after the orders of each axis (a derived summary).
  std::string describe() const override {
    std::string orders;
    for (int axis = 0; axis < 3; ++axis) {
      const ArmaModel& model = parameters().axes[axis];
      orders += kind_ == Kind::kAr ? fmt::format("{} AR({}), ", kAxisNames[axis], model.ar.size())
                                   : fmt::format("{} ARMA({}, {}), ", kAxisNames[axis],
                                                 model.ar.size(), model.ma.size());
    }
    const std::string table = TabulatedNoiseModel::describe();
    const auto colon = table.find(": ");
    return table.substr(0, colon + 2) + orders + table.substr(colon + 2);
  }

 private:
  Kind kind_;
  std::array<ArmaStateSpace, 3> spaces_;
  std::array<int, 3> offsets_{};  ///< first augmented index of each axis block
  int size_ = 0;
  Eigen::MatrixXd initial_;             ///< stationary covariance, natural units^2
  mutable long cached_steps_ = 0;       ///< block count of the cached transition (0: I, 0)
  mutable Eigen::MatrixXd cached_phi_;  ///< A^k per axis block
  mutable Eigen::MatrixXd cached_q_;    ///< k-step noise per axis block, natural units^2
};

}  // namespace

std::string_view type_name(Kind kind) { return kind == Kind::kAr ? "ar" : "arma"; }

int samples_per_block(double interval_s, double rate_hz, const std::string& pointer) {
  const double samples = interval_s * rate_hz;
  const long whole = std::lround(samples);
  if (whole < 1 || std::abs(samples - static_cast<double>(whole)) > 1e-6 * samples) {
    throw ConfigError(pointer + ": found " + nlohmann::json(interval_s).dump() +
                      "; expected a whole multiple of the sample period " +
                      nlohmann::json(1.0 / rate_hz).dump() + " s");
  }
  return static_cast<int>(whole);
}

const ParamTable<ArmaNoiseParams>& constant_params_table() {
  static const ParamTable<ArmaNoiseParams> table{
      scalar(&ArmaNoiseParams::interval_s, "interval_s", ParamUnit::fixed("s"), Bound::kPositive,
             0.1,
             "block length T of the modelled series; keep it the filter's covariance interval"),
      per_axis(&ArmaNoiseParams::k, "K", ParamUnit::of(ParameterDimension::kRatePerRootTime),
               Bound::kNonNegative, 0.0, "rate random walk of the core bias (not fitted)"),
  };
  return table;
}

const ParamTable<ArmaNoiseParams>& model_table(Kind kind) {
  static const auto make = [](const ParamTable<ArmaModel>& axis_table) {
    return constant_params_table().plus(ParamTable<ArmaNoiseParams>{
        axis_groups(&ArmaNoiseParams::axes, "axes", axis_table, "the model of each axis"),
    });
  };
  static const ParamTable<ArmaNoiseParams> ar = make(kArAxisTable);
  static const ParamTable<ArmaNoiseParams> arma = make(kArmaAxisTable);
  return kind == Kind::kAr ? ar : arma;
}

ArmaNoiseParams read_model_params(Kind kind, const nlohmann::json& json,
                                  const NoiseModelContext& context) {
  ParamReader reader(json, context.params_pointer);
  ArmaNoiseParams params;
  model_table(kind).read(reader, sensor_quantity(context.group), params);
  reader.finish();
  if (context.imu_rate_hz > 0.0) {
    samples_per_block(params.interval_s, context.imu_rate_hz, reader.pointer("interval_s"));
  }
  check_axes(params, reader.pointer("axes"));
  return params;
}

std::array<std::vector<double>, 3> block_averaged_axes(const CalibrationRecord& record,
                                                       double interval_s, int min_blocks,
                                                       const std::string& interval_pointer) {
  const int block = samples_per_block(interval_s, record.rate_hz, interval_pointer);
  std::array<std::vector<double>, 3> series;
  for (int axis = 0; axis < 3; ++axis) {
    series[axis] = demeaned(block_means(record.axes[axis], block));
    if (static_cast<int>(series[axis].size()) < min_blocks) {
      throw InputError(record.source + ": axis " + kAxisNames[axis] + " has " +
                       std::to_string(series[axis].size()) + " blocks of " +
                       nlohmann::json(interval_s).dump() + " s; the fit needs at least " +
                       std::to_string(min_blocks) + " (use a longer record)");
    }
  }
  return series;
}

std::unique_ptr<NoiseModelPlugin> make_model(Kind kind, SensorGroup group,
                                             const ArmaNoiseParams& params) {
  return std::make_unique<ArmaNoise>(kind, group, params);
}

}  // namespace stochnav::plugin::arma_noise

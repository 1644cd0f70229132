#include "arma_noise_model.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav::plugin::arma_noise {
namespace {

constexpr const char* kAxisNames[] = {"x", "y", "z"};

using stochnav::plugin::parameters_close;

bool parameters_close(const std::vector<double>& a, const std::vector<double>& b, double rel_tol) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!parameters_close(a[i], b[i], rel_tol)) return false;
  }
  return true;
}

double reported(SensorGroup group, ParameterDimension dimension, double natural) {
  return to_reported(sensor_quantity(group), dimension, natural);
}

class ArmaNoise final : public NoiseModelPlugin {
 public:
  ArmaNoise(Kind kind, SensorGroup group, const ArmaNoiseParams& params)
      : NoiseModelPlugin(group), kind_(kind), params_(params) {
    for (int axis = 0; axis < 3; ++axis) {
      spaces_[axis] = state_space(params_.axes[axis]);
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
    for (int i = 0; i < 3; ++i) q_bias(i, i) = params_.k[i] * params_.k[i] * dt_s;
  }

  void augmented_transition(double, double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                            Eigen::Ref<Eigen::MatrixXd> q_d) const override {
    const long steps = std::lround(dt_s / params_.interval_s);
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

  nlohmann::json params() const override { return write_model_params(kind_, group(), params_); }

  std::string describe() const override {
    const auto quantity = sensor_quantity(group());
    std::string text = fmt::format("{} ({}): interval {:.6g} s;", type(),
                                   sensor_group_name(group()), params_.interval_s);
    for (int axis = 0; axis < 3; ++axis) {
      const ArmaModel& model = params_.axes[axis];
      const std::string orders =
          kind_ == Kind::kAr
              ? fmt::format("AR({}) ar = [{:.6g}]", model.ar.size(), fmt::join(model.ar, ", "))
              : fmt::format("ARMA({}, {}) ar = [{:.6g}], ma = [{:.6g}]", model.ar.size(),
                            model.ma.size(), fmt::join(model.ar, ", "), fmt::join(model.ma, ", "));
      text += fmt::format(" {}: {}, sigma = {:.6g} {}, K = {:.6g} {};", kAxisNames[axis], orders,
                          reported(ParameterDimension::kRate, model.sigma),
                          reported_unit_name(quantity, ParameterDimension::kRate),
                          reported(ParameterDimension::kRatePerRootTime, params_.k[axis]),
                          reported_unit_name(quantity, ParameterDimension::kRatePerRootTime));
    }
    text.pop_back();
    return text;
  }

  bool equals(const NoiseModelPlugin& other, double rel_tol) const override {
    const auto* that = dynamic_cast<const ArmaNoise*>(&other);
    if (that == nullptr || that->kind_ != kind_ || that->group() != group() ||
        !constant_params_table().equal(params_, that->params_, rel_tol)) {
      return false;
    }
    for (int axis = 0; axis < 3; ++axis) {
      const ArmaModel &a = params_.axes[axis], &b = that->params_.axes[axis];
      if (!parameters_close(a.ar, b.ar, rel_tol) || !parameters_close(a.ma, b.ma, rel_tol) ||
          !parameters_close(a.sigma, b.sigma, rel_tol)) {
        return false;
      }
    }
    return true;
  }

 private:
  Kind kind_;
  ArmaNoiseParams params_;
  std::array<ArmaStateSpace, 3> spaces_;
  std::array<int, 3> offsets_{};  ///< first augmented index of each axis block
  int size_ = 0;
  Eigen::MatrixXd initial_;             ///< stationary covariance, natural units^2
  mutable long cached_steps_ = 0;       ///< block count of the cached transition (0: I, 0)
  mutable Eigen::MatrixXd cached_phi_;  ///< A^k per axis block
  mutable Eigen::MatrixXd cached_q_;    ///< k-step noise per axis block, natural units^2
};

std::vector<double> read_coefficients(ParamReader& reader, std::string_view key, bool required) {
  const nlohmann::json& value = reader.raw(key);
  const std::string expected =
      "an array of numbers (" + std::string(required ? "at least one" : "may be empty") + ")";
  if (value.is_null()) {
    if (required) throw ConfigError(reader.pointer(key) + ": missing; expected " + expected);
    return {};
  }
  if (!value.is_array() || (required && value.empty())) {
    throw ConfigError(reader.pointer(key) + ": found " + value.dump() + "; expected " + expected);
  }
  std::vector<double> coefficients;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!value[i].is_number() || !std::isfinite(value[i].get<double>())) {
      throw ConfigError(reader.pointer(key) + "/" + std::to_string(i) + ": found " +
                        value[i].dump() + "; expected a finite number");
    }
    coefficients.push_back(value[i].get<double>());
  }
  return coefficients;
}

ArmaModel read_axis(Kind kind, const nlohmann::json& json, const std::string& pointer,
                    SensorGroup group) {
  ParamReader reader(json, pointer);
  ArmaModel model;
  model.ar = read_coefficients(reader, "ar", kind == Kind::kAr);
  if (kind == Kind::kArma) model.ma = read_coefficients(reader, "ma", false);
  const auto quantity = sensor_quantity(group);
  model.sigma = to_natural(quantity, ParameterDimension::kRate,
                           reader.number("sigma", Bound::kPositive,
                                         reported_unit_name(quantity, ParameterDimension::kRate)));
  reader.finish();
  if (!is_stationary(model.ar)) {
    throw ConfigError(reader.pointer("ar") + ": found " + nlohmann::json(model.ar).dump() +
                      "; expected a stationary AR part (all roots of 1 - sum phi_i z^i outside "
                      "the unit circle)");
  }
  const int r = static_cast<int>(std::max(model.ar.size(), model.ma.size() + 1));
  if (r > kMaxArmaStateSize) {
    throw ConfigError(pointer + ": found max(p, q + 1) = " + std::to_string(r) +
                      " states; expected at most " + std::to_string(kMaxArmaStateSize));
  }
  return model;
}

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

InformationCriterion read_criterion(ParamReader& reader) {
  static constexpr std::string_view kAllowed[] = {"aic", "bic"};
  return reader.choice_or("criterion", "bic", kAllowed) == "aic" ? InformationCriterion::kAic
                                                                 : InformationCriterion::kBic;
}

int read_integer_or(ParamReader& reader, std::string_view key, int fallback, int low, int high) {
  if (!reader.has(key)) return fallback;
  const double value = reader.number(key, Bound::kAny, "");
  if (value != std::round(value) || value < low || value > high) {
    throw ConfigError(reader.pointer(key) + ": found " + nlohmann::json(value).dump() +
                      "; expected an integer in [" + std::to_string(low) + ", " +
                      std::to_string(high) + "]");
  }
  return static_cast<int>(value);
}

ArmaNoiseParams read_model_params(Kind kind, const nlohmann::json& json,
                                  const NoiseModelContext& context) {
  ParamReader reader(json, context.params_pointer);
  ArmaNoiseParams params;
  constant_params_table().read(reader, sensor_quantity(context.group), params);
  if (context.imu_rate_hz > 0.0) {
    samples_per_block(params.interval_s, context.imu_rate_hz, reader.pointer("interval_s"));
  }
  const nlohmann::json& axes = reader.raw("axes");
  const std::string axes_pointer = reader.pointer("axes");
  if (axes.is_null()) {
    throw ConfigError(axes_pointer + ": missing; expected an array of 3 per-axis objects " +
                      "{\"ar\": [...], " + (kind == Kind::kArma ? "\"ma\": [...], " : "") +
                      "\"sigma\": s}");
  }
  if (!axes.is_array() || axes.size() != 3) {
    throw ConfigError(axes_pointer + ": found " + axes.dump() +
                      "; expected an array of 3 per-axis objects (x, y, z)");
  }
  for (std::size_t axis = 0; axis < 3; ++axis) {
    params.axes[axis] =
        read_axis(kind, axes[axis], axes_pointer + "/" + std::to_string(axis), context.group);
  }
  reader.finish();
  return params;
}

nlohmann::json write_model_params(Kind kind, SensorGroup group, const ArmaNoiseParams& params) {
  nlohmann::json axes = nlohmann::json::array();
  for (int axis = 0; axis < 3; ++axis) {
    const ArmaModel& model = params.axes[axis];
    nlohmann::json entry = {{"ar", model.ar},
                            {"sigma", reported(group, ParameterDimension::kRate, model.sigma)}};
    if (kind == Kind::kArma) entry["ma"] = model.ma;
    axes.push_back(entry);
  }
  nlohmann::json out = constant_params_table().to_json(params, sensor_quantity(group));
  out["axes"] = std::move(axes);
  return out;
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

// Out-of-line pieces of the plugin interfaces. The destructors live here so that one typeinfo
// and one vtable anchor of each interface exist, in the core library, for every plugin.

#include "stochnav/plugin/plugin_api.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/params.hpp"

namespace stochnav::plugin {

std::string_view plugin_kind_name(PluginKind kind) {
  switch (kind) {
    case PluginKind::kNoiseModel:
      return "noise";
    case PluginKind::kAid:
      return "aid";
  }
  return "unknown";
}

std::string_view sensor_group_name(SensorGroup group) {
  return group == SensorGroup::kGyro ? "gyro" : "accel";
}

std::optional<SensorGroup> parse_sensor_group(std::string_view name) {
  if (name == "gyro") return SensorGroup::kGyro;
  if (name == "accel") return SensorGroup::kAccel;
  return std::nullopt;
}

Quantity sensor_quantity(SensorGroup group) {
  return group == SensorGroup::kGyro ? Quantity::kAngularRate : Quantity::kSpecificForce;
}

NoiseModelPlugin::~NoiseModelPlugin() = default;

void NoiseModelPlugin::bias_walk_covariance(double, double,
                                            Eigen::Ref<Eigen::MatrixXd> q_bias) const {
  q_bias.setZero();
}

void NoiseModelPlugin::augmented_transition(double, double, Eigen::Ref<Eigen::MatrixXd>,
                                            Eigen::Ref<Eigen::MatrixXd>) const {}

void NoiseModelPlugin::augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd>) const {}

void NoiseModelPlugin::augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd>) const {}

void NoiseModelPlugin::on_update(const UpdateFeedback&) {}

double NoiseModelPlugin::reported(ParameterDimension dimension, double natural) const {
  return to_reported(sensor_quantity(group_), dimension, natural);
}

std::string NoiseModelPlugin::reported_unit(ParameterDimension dimension) const {
  return reported_unit_name(sensor_quantity(group_), dimension);
}

std::unique_ptr<NoiseModelPlugin> fit_not_supported(const CalibrationRecord&, const nlohmann::json&,
                                                    const NoiseModelContext& context) {
  throw ConfigError(context.params_pointer +
                    ": this noise-model plugin cannot fit its model from data; remove the "
                    "\"fit\" entry and give its parameters in \"params\"");
}

AidPlugin::~AidPlugin() = default;

double chi_square_quantile(double probability, int dof) {
  if (!(probability > 0.0 && probability < 1.0) || dof < 1) {
    throw std::invalid_argument("chi_square_quantile: probability must be in (0, 1), dof >= 1");
  }
  return boost::math::quantile(boost::math::chi_squared(dof), probability);
}

const ParamTable<NisGateParams>& nis_gate_table() {
  static const ParamTable<NisGateParams> table{
      flag(&NisGateParams::enabled, "nis_gate", true, "reject updates whose NIS is too large"),
      scalar(&NisGateParams::probability, "nis_probability", ParamUnit::fixed(""), Bound::kOpenUnit,
             kDefaultGateProbability,
             "gate at this chi-square quantile (dof: the measurement size)"),
      scalar(&NisGateParams::threshold, "nis_threshold", ParamUnit::fixed(""), Bound::kPositive,
             kDerived, "gate at this NIS, overriding nis_probability"),
  };
  return table;
}

NisGate nis_gate(const NisGateParams& params, int measurement_size) {
  NisGate gate;
  gate.enabled = params.enabled;
  gate.threshold = std::isnan(params.threshold)
                       ? chi_square_quantile(params.probability, measurement_size)
                       : params.threshold;
  return gate;
}

NisGate read_nis_gate(ParamReader& params, int measurement_size) {
  NisGateParams gate;
  nis_gate_table().read(params, gate);
  return nis_gate(gate, measurement_size);
}

}  // namespace stochnav::plugin

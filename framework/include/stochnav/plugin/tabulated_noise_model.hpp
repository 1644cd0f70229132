#pragma once
// A noise model whose parameters are a ParamTable's params struct: params(), describe() and
// equals() follow from the table, so a plugin writes only its maths and a factory of three lines:
//
//   class WhiteNoise final : public TabulatedNoiseModel<WhiteParams> {
//    public:
//     WhiteNoise(SensorGroup group, const WhiteParams& params)
//         : TabulatedNoiseModel(group, kWhiteTable, params) {}
//     std::string_view type() const override { return "white"; }
//     void white_noise_covariance(...) const override { ... parameters().n ... }
//   };
//   std::unique_ptr<NoiseModelPlugin> make_white(const nlohmann::json& json,
//                                                const NoiseModelContext& context) {
//     return std::make_unique<WhiteNoise>(context.group, parse_params(kWhiteTable, json, context));
//   }
//
// describe() reads "<type> (<group>): <table.describe()>"; a model with more to say (state it
// adapts, derived quantities) overrides it. equals() holds for the same type, group and table
// with every parameter within rel_tol.

#include <nlohmann/json.hpp>
#include <string>

#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/param_table.hpp"

namespace stochnav::plugin {

/// ParamTable::parse of a factory's params: the context's group picks the reporting units, its
/// params_pointer prefixes every error.
template <class Params>
Params parse_params(const ParamTable<Params>& table, const nlohmann::json& params,
                    const NoiseModelContext& context) {
  return table.parse(params, context.params_pointer, sensor_quantity(context.group));
}

template <class Params>
class TabulatedNoiseModel : public NoiseModelPlugin {
 public:
  nlohmann::json params() const override {
    return table_.to_json(params_, sensor_quantity(group()));
  }

  std::string describe() const override {
    return std::string(type()) + " (" + std::string(sensor_group_name(group())) +
           "): " + table_.describe(params_, sensor_quantity(group()));
  }

  bool equals(const NoiseModelPlugin& other, double rel_tol) const override {
    const auto* that = dynamic_cast<const TabulatedNoiseModel*>(&other);
    return that != nullptr && &that->table_ == &table_ && that->type() == type() &&
           that->group() == group() && table_.equal(params_, that->params_, rel_tol);
  }

 protected:
  /// `table` must outlive the model (a namespace-scope constant of the plugin).
  TabulatedNoiseModel(SensorGroup group, const ParamTable<Params>& table, const Params& params)
      : NoiseModelPlugin(group), table_(table), params_(params) {}

  /// The parameters, natural SI units.
  const Params& parameters() const { return params_; }
  const ParamTable<Params>& table() const { return table_; }

 private:
  const ParamTable<Params>& table_;
  Params params_;
};

}  // namespace stochnav::plugin

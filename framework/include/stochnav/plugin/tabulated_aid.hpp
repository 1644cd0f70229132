#pragma once
// An aid whose parameters are a ParamTable's params struct, with the NIS gate keys of every aid
// (nis_gate_table(): "nis_gate", "nis_probability", "nis_threshold") lifted in: parsing with
// units, the gate, describe(), params() and equals() follow from the table, so a plugin writes
// only its maths and a factory of a few lines:
//
//   struct SurveyParams {
//     double sigma_deg;                      ///< deg (the maths converts)
//     stochnav::plugin::NisGateParams gate;  ///< the member the gate keys are read into
//   };
//   const auto kSurveyTable = stochnav::plugin::aid_param_table<SurveyParams>({
//       scalar(&SurveyParams::sigma_deg, "sigma_deg", ParamUnit::fixed("deg"), Bound::kPositive,
//              0.1, "1-sigma of the surveyed inclination")});
//
//   class SurveyAid final : public stochnav::plugin::TabulatedAid<SurveyParams> {
//    public:
//     SurveyAid(const SurveyParams& params, ...) : TabulatedAid(kSurveyTable, params, 1) {}
//     std::string_view type() const override { return "survey"; }
//     int measurement_size() const override { return 1; }
//     bool has_measurement(double t_s) const override { ... }
//     bool measure(...) const override { ... parameters().sigma_deg ... }
//   };
//   std::unique_ptr<AidPlugin> make_survey(const nlohmann::json& json, const AidContext& context) {
//     return std::make_unique<SurveyAid>(parse_aid_params(kSurveyTable, json, context), ...);
//   }
//
// describe() reads "<type>: <detail()>; <table.describe()>" ("<type>: <table.describe()>" when
// detail() is empty). equals() holds for the same type and table with every parameter within
// rel_tol.

#include <cmath>
#include <initializer_list>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/param_table.hpp"

namespace stochnav::plugin {

/// The table of an aid's own entries followed by the NIS gate keys, read into Params::gate (a
/// NisGateParams member).
template <class Params>
ParamTable<Params> aid_param_table(std::initializer_list<ParamEntry<Params>> entries) {
  return ParamTable<Params>(entries).plus(lift(&Params::gate, nis_gate_table()));
}

/// ParamTable::parse_into of an aid factory's params, errors prefixed with the context's
/// params_pointer. `defaults` holds what absent keys with Absent::kKeep keep (a default site
/// taken from the run's initial state).
template <class Params>
Params parse_aid_params(const ParamTable<Params>& table, const nlohmann::json& params,
                        const AidContext& context, Params defaults = {}) {
  table.parse_into(params, context.params_pointer, Quantity::kPlain, defaults);
  return defaults;
}

template <class Params>
class TabulatedAid : public AidPlugin {
 public:
  std::string describe() const override {
    const std::string more = detail();
    return std::string(type()) + ": " + (more.empty() ? "" : more + "; ") +
           table_.describe(params_);
  }

  /// The params object the factory reads back into equal parameters (the gate keys included;
  /// a value left for the factory to derive, such as an absent nis_threshold, is left out).
  nlohmann::json params() const {
    nlohmann::json json = table_.to_json(params_);
    for (auto it = json.begin(); it != json.end();) {
      const bool derived = it->is_number_float() && std::isnan(it->template get<double>());
      it = derived ? json.erase(it) : std::next(it);
    }
    return json;
  }

  /// Same type, same table, every parameter within rel_tol, the gates' thresholds compared as
  /// the gates apply them (a derived threshold is the chi-square quantile).
  bool equals(const AidPlugin& other, double rel_tol) const {
    const auto* that = dynamic_cast<const TabulatedAid*>(&other);
    if (that == nullptr || &that->table_ != &table_ || that->type() != type()) return false;
    Params mine = params_;
    Params theirs = that->params_;
    mine.gate.threshold = gate().threshold;
    theirs.gate.threshold = that->gate().threshold;
    return table_.equal(mine, theirs, rel_tol);
  }

 protected:
  /// `table` must outlive the aid (a namespace-scope constant of the plugin); the gate is
  /// nis_gate(params.gate, measurement_size).
  TabulatedAid(const ParamTable<Params>& table, const Params& params, int measurement_size)
      : AidPlugin(nis_gate(params.gate, measurement_size)), table_(table), params_(params) {}

  /// What describe() says before the parameters (what the aid measures, from which data); "" for
  /// nothing.
  virtual std::string detail() const { return ""; }

  /// The parameters, natural SI units.
  const Params& parameters() const { return params_; }
  const ParamTable<Params>& table() const { return table_; }

 private:
  const ParamTable<Params>& table_;
  Params params_;
};

}  // namespace stochnav::plugin

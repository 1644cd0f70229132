#include "stochnav/fit/fit_result_json.hpp"

#include <cmath>
#include <string>

#include "stochnav/io/json_numbers.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

using nlohmann::json;

json term_names(const std::vector<TermType>& types) {
  json names = json::array();
  for (TermType type : types) names.push_back(std::string(term_type_name(type)));
  return names;
}

json readoff_json(const SlopeReadoff& readoff, Quantity quantity, ParameterDimension dimension) {
  return {{"value", number_or_null(to_reported(quantity, dimension, readoff.value))},
          {"unit", reported_unit_name(quantity, dimension)},
          {"tau_s", readoff.tau_s}};
}

}  // namespace

json fit_result_to_json(const FitResult& result) {
  json document = to_json(result.model);
  const Quantity quantity = quantity_of(result.model.unit);
  for (std::size_t i = 0; i < result.model.terms.size() && i < result.sigma.size(); ++i) {
    json& term = document["terms"][i];
    const auto specs = parameter_specs(term_type(result.model.terms[i]));
    for (std::size_t k = 0; k < specs.size(); ++k) {
      const auto sigma = parameter_value(result.sigma[i], k);
      if (!sigma || !term.contains(std::string(specs[k].name))) continue;
      term[std::string(specs[k].name) + "_sigma"] =
          number_or_null(to_reported(quantity, specs[k].dimension, *sigma));
    }
  }

  const FitDiagnostics& d = result.diagnostics;
  json selection = json::array();
  for (const auto& step : d.selection) {
    selection.push_back({{"terms", term_names(step.terms)},
                         {"criterion", number_or_null(step.criterion)},
                         {"accepted", step.accepted}});
  }
  const auto& r = d.readoffs;
  const bool gmwm = d.method == FitMethod::kGmwm;
  document["method"] = std::string(fit_method_name(d.method));
  if (!result.ranking.empty()) {
    json ranking = json::array();
    for (const auto& entry : result.ranking) {
      ranking.push_back({{"terms", term_names(entry.terms)},
                         {"wic", number_or_null(entry.wic)},
                         {"objective", number_or_null(entry.objective)},
                         {"dropped_terms", entry.dropped_terms},
                         {"failed", entry.failed}});
    }
    document["ranking"] = std::move(ranking);
  }
  document["diagnostics"] = {
      {"cost", number_or_null(d.cost)},
      {"chi_square", number_or_null(d.chi_square)},
      {"points", d.points},
      {"parameters", d.parameters},
      {"criterion", gmwm ? std::string("wic") : std::string(criterion_name(d.criterion))},
      {"criterion_value", number_or_null(d.criterion_value)},
      {"loss", std::string(robust_loss_name(d.loss))},
      {"loss_scale", d.loss_scale},
      {"iterations", d.iterations},
      {"converged", d.converged},
      {"automatic", d.automatic},
      {"chosen_terms", term_names(d.chosen_terms)},
      {"slope_readoffs",
       {{"Q", readoff_json(r.quantization, quantity, ParameterDimension::kAngle)},
        {"N", readoff_json(r.angle_random_walk, quantity, ParameterDimension::kAnglePerRootTime)},
        {"B", readoff_json(r.bias_instability, quantity, ParameterDimension::kRate)},
        {"K", readoff_json(r.rate_random_walk, quantity, ParameterDimension::kRatePerRootTime)},
        {"R", readoff_json(r.rate_ramp, quantity, ParameterDimension::kRatePerTime)}}},
      {"selection", std::move(selection)},
      {"warnings", d.warnings},
      {"failed", d.failed()},
      {"failure", d.failure()},
      {"dropped_terms", d.dropped_terms},
      {"at_bound", d.at_bound},
      {"undetermined", d.undetermined},
  };
  if (gmwm) {
    document["diagnostics"].erase("slope_readoffs");  // read off an Allan curve: not made here
    // The objective is the J-test statistic (fit/gmwm_fit.hpp): chi-square with dof degrees.
    document["diagnostics"]["objective"] = number_or_null(d.cost);
    document["diagnostics"]["gauss_markov_sampling"] =
        std::string(gauss_markov_sampling_name(d.gauss_markov_sampling));
    document["diagnostics"]["j_test"] = {
        {"statistic", number_or_null(d.chi_square)},
        {"dof", d.points > d.parameters ? d.points - d.parameters : 0},
        {"p_value", number_or_null(d.chi_square_p_value())}};
  }
  return document;
}

}  // namespace stochnav

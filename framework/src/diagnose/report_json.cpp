#include "stochnav/diagnose/report_json.hpp"

#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

nlohmann::json range_json(const std::optional<std::array<double, 2>>& range) {
  if (!range) return nullptr;
  return nlohmann::json::array({(*range)[0], (*range)[1]});
}

}  // namespace

nlohmann::json diagnose_report_json(const DiagnoseResult& result) {
  nlohmann::json iterations = nlohmann::json::array();
  for (const auto& step : result.iterations) {
    nlohmann::json added = to_json(step.added_term, step.after.model.unit);
    // Uncertainties in the parameter's reporting unit, "<name>_sigma" as in fit output.
    const auto specs = parameter_specs(term_type(step.added_term));
    for (const auto& [name, sigma] : step.added_term_sigma) {
      for (const auto& spec : specs) {
        if (spec.name != name) continue;
        added[name + "_sigma"] =
            to_reported(quantity_of(step.after.model.unit), spec.dimension, sigma);
      }
    }
    nlohmann::json iteration = {{"effect", std::string(term_type_name(step.effect))},
                                {"evidence", step.evidence},
                                {"tau_range_s", range_json(step.tau_range_s)},
                                {"time_range_s", range_json(step.time_range_s)},
                                {"added_term", std::move(added)},
                                {"gap_before", step.gap_before},
                                {"gap_after", step.gap_after}};
    if (!step.added_term_at_bound.empty()) {
      iteration["added_term_at_bound"] = step.added_term_at_bound;
    }
    iterations.push_back(std::move(iteration));
  }
  return {{"consistent", result.consistent},
          {"gap_initial", result.initial.gap.value},
          {"gap_final", result.final_assessment().gap.value},
          {"iterations", std::move(iterations)},
          {"final_model", to_json(result.final_model())}};
}

}  // namespace stochnav

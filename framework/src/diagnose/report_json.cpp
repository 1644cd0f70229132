#include "stochnav/diagnose/report_json.hpp"

#include <fmt/format.h>

#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

nlohmann::json range_json(const std::optional<std::array<double, 2>>& range) {
  if (!range) return nullptr;
  return nlohmann::json::array({(*range)[0], (*range)[1]});
}

nlohmann::json outliers_json(const WaveletOutlierCheck& check, Unit unit) {
  nlohmann::json levels = nlohmann::json::array();
  for (const WaveletLevelSplit& level : check.levels) {
    levels.push_back({{"scale_s", level.scale_s},
                      {"edf", level.edf},
                      {"classical", level.classical},
                      {"classical_lo", level.classical_lo},
                      {"classical_hi", level.classical_hi},
                      {"robust", level.robust},
                      {"robust_lo", level.robust_lo},
                      {"robust_hi", level.robust_hi},
                      {"excess", level.excess()},
                      {"tested", level.tested},
                      {"flagged", level.flagged}});
  }
  nlohmann::json worst = nlohmann::json::array();
  for (const OutlierSample& sample : check.worst) {
    worst.push_back({{"time_s", sample.time_s}, {"index", sample.index}, {"z", sample.z}});
  }
  const auto [low, high] = check.flagged_scale_range_s();
  const auto [excess, at] = check.largest_excess();
  return {{"contaminated", check.contaminated},
          {"explained_by_nonstationary", check.explained_by_nonstationary},
          {"scale_range_s", check.contaminated ? range_json(std::array<double, 2>{low, high})
                                               : nlohmann::json(nullptr)},
          {"largest_excess", excess},
          {"largest_excess_scale_s", check.contaminated ? nlohmann::json(at) : nullptr},
          {"wv_unit", fmt::format("({})^2", unit_name(unit))},
          {"levels", std::move(levels)},
          {"z_threshold", check.z_threshold},
          {"differences_beyond", check.differences_beyond},
          {"worst_samples", std::move(worst)},
          {"summary", check.summary()}};
}

nlohmann::json short_tau_json(const ShortTauGaussMarkovCheck& check, Unit unit) {
  nlohmann::json added = nullptr;
  if (check.named) {
    added = to_json(check.term, unit);
    const Quantity quantity = quantity_of(unit);
    added["sigma_sigma"] = to_reported(quantity, ParameterDimension::kRate, check.sigma_sigma);
    added["tau_c_sigma"] = check.tau_c_sigma;
  }
  return {{"applicable", check.applicable},
          {"named", check.named},
          {"effect", check.named ? nlohmann::json("gauss_markov") : nlohmann::json(nullptr)},
          {"added_term", std::move(added)},
          {"tau_c_on_range_end", check.at_lower_end   ? nlohmann::json("lower")
                                 : check.at_upper_end ? nlohmann::json("upper")
                                                      : nlohmann::json(nullptr)},
          {"in_model", check.in_model},
          {"robust_wv", check.robust},
          {"scales", check.scales},
          {"objective_without", check.objective_without},
          {"objective_with", check.objective_with},
          {"threshold", check.threshold},
          {"largest_share", check.largest_share},
          {"largest_share_scale_s", check.largest_share_scale_s},
          {"lag1_model", check.lag1_model},
          {"lag1_record", check.lag1_record},
          {"summary", check.summary(unit)}};
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
  nlohmann::json report = {{"consistent", result.consistent},
                           {"gap_initial", result.initial.gap.value},
                           {"gap_final", result.final_assessment().gap.value},
                           {"iterations", std::move(iterations)},
                           {"final_model", to_json(result.final_model())}};
  const Unit unit = result.initial.model.unit;
  if (result.wavelet_outliers) {
    report["wavelet_outliers"] = outliers_json(*result.wavelet_outliers, unit);
  }
  if (result.short_tau_gauss_markov) {
    report["short_tau_gauss_markov"] = short_tau_json(*result.short_tau_gauss_markov, unit);
  }
  return report;
}

}  // namespace stochnav

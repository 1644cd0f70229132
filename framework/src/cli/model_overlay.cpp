#include "model_overlay.hpp"

#include <fmt/format.h>

#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/model/allan_variance.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/report/gnuplot.hpp"
#include "stochnav/io/json_document.hpp"

namespace stochnav::cli {

ModelOverlay model_overlay(const std::string& model_path, const Record& record, double tau_min_s,
                           double tau_max_s, ModelCurve curve) {
  NoiseModel model;
  try {
    model = noise_model_from_json(read_json_document(model_path, "--fit"));
  } catch (const ConfigError& error) {
    throw ConfigError(model_path + ": " + error.what());
  }
  if (quantity_of(model.unit) != quantity_of(record.unit)) {
    throw ConfigError(model_path + ": the model is in " + unit_name(model.unit) +
                      " but the record in " + unit_name(record.unit) + "; pass a matching --unit");
  }
  const double record_per_natural = 1.0 / si_per_unit(record.unit);
  constexpr int kPoints = 120;
  std::vector<double> tau(kPoints);
  for (int i = 0; i < kPoints; ++i) {
    tau[i] = tau_min_s * std::pow(tau_max_s / tau_min_s, i / (kPoints - 1.0));
  }
  // The Haar filter at scale tau is the Allan difference at tau / 2, halved (wavelet_variance.hpp).
  auto deviation_curve = [&](auto&& avar_at) {
    std::vector<double> values(kPoints);
    for (int i = 0; i < kPoints; ++i) {
      values[i] = curve == ModelCurve::kAllanDeviation
                      ? std::sqrt(avar_at(tau[i])) * record_per_natural
                      : avar_at(tau[i] / 2.0) / 2.0 * record_per_natural * record_per_natural;
    }
    return values;
  };

  ModelOverlay overlay;
  const auto total = deviation_curve([&](double t) { return allan_variance(model, t); });
  overlay.datablocks += gnuplot_datablock("model_total", {&tau, &total});
  overlay.plot_clauses +=
      ", $model_total using 1:2 with lines lw 2.5 lc rgb '#d62728' title 'fitted model'";
  int index = 0;
  for (const NoiseTerm& term : model.terms) {
    if (term_type(term) == TermType::kNonstationary) continue;
    const auto term_curve = deviation_curve([&](double t) { return allan_variance(term, t); });
    const std::string name = fmt::format("term{}", index++);
    overlay.datablocks += gnuplot_datablock(name, {&tau, &term_curve});
    overlay.plot_clauses += fmt::format(", ${} using 1:2 with lines dt 2 lw 1.5 title '{}' noenhanced", name,
                                        term_type_name(term_type(term)));
  }
  return overlay;
}

}  // namespace stochnav::cli

#include "stochnav/diagnose/report_markdown.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stochnav/diagnose/effective_model.hpp"

namespace stochnav {
namespace {

constexpr const char* kGapDefinition =
    "**The gap.** At the octave averaging times tau_i (m = 1, 2, 4, ... up to N/4) the measured "
    "overlapping Allan variance A_i is compared with the model's closed form mu_i. The exact "
    "covariance V of the estimates for a record of this length under the model gives each point "
    "its degrees of freedom nu_i = 2 mu_i^2 / V_ii, and z_i = [ln A_i - ln mu_i - b(nu_i)] / "
    "s(nu_i), with b and s the mean and standard deviation of ln(chi2(nu)/nu) (digamma, "
    "trigamma), is about N(0, 1) when the model is right. G_avar = mean z_i^2. The points are "
    "correlated (R = V normalised), so G_avar is treated as chi2(nu_avar)/nu_avar with the "
    "Satterthwaite effective dof nu_avar = M^2 / tr(R^2). The stationarity test cuts the record "
    "into windows and compares their Allan variances at tau0 (the DAVAR at the shortest tau), "
    "each with its variance estimated from the window's own data, after dividing out the model's "
    "nonstationary scaling: G_stat = chi-square / (windows - 1). The gap is max(G_avar, G_stat): "
    "about 1 for a consistent model. The model is consistent when each part is below the "
    "(1 - alpha/2) quantile of its chi2(nu)/nu (false-alarm probability at most alpha). A "
    "candidate term is kept only if it lowers the pooled chi-square nu_avar G_avar + nu_stat "
    "G_stat by more than the (1 - alpha) quantile of chi2(p), p its parameter count, and shrinks "
    "the gap. Simulated records of the model (several seeds, same length and rate) give the "
    "band drawn in the plots; they are a check, the gap uses the closed forms.\n";

std::string trimmed(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

std::string gap_summary(const Gap& gap) {
  return fmt::format(
      "gap **{:.3g}** ({}): AVAR part G_avar {:.3g} on {:.1f} effective dof (consistent "
      "below {:.3g}), stationarity part G_stat {:.3g} on {:.0f} dof (below {:.3g}; p = {:.2g})",
      gap.value, gap.consistent ? "consistent" : "not consistent", gap.avar.reduced_chi_square,
      gap.avar.effective_dof, gap.avar_threshold, gap.stationarity.reduced_chi_square,
      gap.stationarity.dof, gap.stationarity_threshold, gap.stationarity.p_value);
}

std::string model_lines(const NoiseModel& model) {
  std::string text;
  for (const NoiseTerm& term : model.terms) {
    text += "- " + trimmed(describe(term, quantity_of(model.unit))) + "\n";
  }
  if (model.terms.empty()) text += "- (no terms)\n";
  return text;
}

// Table of the octave points: measured ADEV with its interval, the model, the simulated band.
std::string point_table(const MeasuredStatistics& measured, const ModelAssessment& assessment) {
  const double per_natural = 1.0 / si_per_unit(measured.unit);
  std::string text = fmt::format(
      "| tau (s) | measured ADEV [68.3 % interval] ({0}) | model ADEV ({0}) | simulated "
      "[min, max] ({0}) | z |\n|---|---|---|---|---|\n",
      unit_name(measured.unit));
  for (const auto& point : assessment.gap.avar.points) {
    const auto row = std::find_if(
        measured.octave.begin(), measured.octave.end(),
        [&](const auto& p) { return std::abs(p.tau_s - point.tau_s) < 1e-12 * point.tau_s; });
    std::string interval = "";
    if (row != measured.octave.end() && std::isfinite(row->lower)) {
      interval = fmt::format(" [{:.4g}, {:.4g}]", row->lower, row->upper);
    }
    std::string band = "-";
    const auto& b = assessment.band;
    for (std::size_t j = 0; j < b.tau_s.size() && j < b.low.size(); ++j) {
      if (std::abs(b.tau_s[j] - point.tau_s) < 1e-9 * point.tau_s) {
        band = fmt::format("[{:.4g}, {:.4g}]", b.low[j] * per_natural, b.high[j] * per_natural);
      }
    }
    text += fmt::format("| {:.4g} | {:.4g}{} | {:.4g} | {} | {:+.2f} |\n", point.tau_s,
                        std::sqrt(point.avar_measured) * per_natural, interval,
                        std::sqrt(point.avar_model) * per_natural, band, point.z);
  }
  return text;
}

}  // namespace

namespace {

// The wavelet-variance findings (DiagnoseResult::wavelet_outliers, short_tau_gauss_markov).
std::string wavelet_section(const DiagnoseResult& result) {
  if (!result.wavelet_outliers && !result.short_tau_gauss_markov) return {};
  std::string md = "\n## Wavelet variance: outliers and short-tau correlation\n\n";
  const Unit unit = result.initial.model.unit;
  if (const auto& check = result.wavelet_outliers) {
    md += check->summary() + "\n\n";
    md += fmt::format(
        "| scale (s) | classical [95 %] (({0})^2) | robust [95 %] (({0})^2) | excess | flagged |\n"
        "|---|---|---|---|---|\n",
        unit_name(unit));
    for (const WaveletLevelSplit& level : check->levels) {
      if (!level.tested) continue;
      md += fmt::format(
          "| {:.4g} | {:.4g} [{:.4g}, {:.4g}] | {:.4g} [{:.4g}, {:.4g}] | {:+.1f} % | {} |\n",
          level.scale_s, level.classical, level.classical_lo, level.classical_hi, level.robust,
          level.robust_lo, level.robust_hi, 100.0 * level.excess(), level.flagged ? "yes" : "");
    }
    md += "\n";
  }
  if (const auto& check = result.short_tau_gauss_markov) md += check->summary(unit) + "\n";
  return md;
}

}  // namespace

std::string diagnose_report_markdown(const DiagnoseResult& result, const std::string& source,
                                     const std::string& model_source,
                                     const DiagnosePlotFiles& plots) {
  const MeasuredStatistics& measured = result.measured;
  std::string md = "# stochnav diagnose\n\n";
  md += fmt::format("Record: `{}` — {} samples at {} Hz ({:.1f} s), unit {}.  \n", source,
                    measured.samples, measured.rate_hz, measured.duration_s,
                    unit_name(measured.unit));
  md += fmt::format("Model: `{}`.\n\n", model_source);
  md += fmt::format("**Result: {}.** {}\n\n", result.consistent ? "consistent" : "not consistent",
                    result.conclusion);
  md += fmt::format("Gap: {:.3g} initially, {:.3g} at the end, after {} step(s).\n\n",
                    result.initial.gap.value, result.final_assessment().gap.value,
                    result.iterations.size());
  md += kGapDefinition;
  md += "\n## The model as given\n\n" + model_lines(result.initial.model) + "\n";
  md += gap_summary(result.initial.gap) + ".\n\n";
  md += point_table(measured, result.initial) + "\n";
  if (!plots.initial.empty()) md += fmt::format("![measured vs model]({})\n\n", plots.initial);

  for (std::size_t i = 0; i < result.iterations.size(); ++i) {
    const DiagnoseIteration& step = result.iterations[i];
    md += fmt::format("## Step {}: {}\n\n", i + 1, term_type_name(step.effect));
    md += step.evidence + "\n\n";
    if (step.tau_range_s) {
      md += fmt::format("- tau range: {:.4g} .. {:.4g} s\n", (*step.tau_range_s)[0],
                        (*step.tau_range_s)[1]);
    }
    if (step.time_range_s) {
      md += fmt::format("- time range: {:.1f} .. {:.1f} s\n", (*step.time_range_s)[0],
                        (*step.time_range_s)[1]);
    }
    md += fmt::format("- added: {}{}\n",
                      trimmed(describe(step.added_term, quantity_of(step.after.model.unit))),
                      step.refitted ? " (the other terms refitted with it)" : "");
    md += fmt::format("- gap: {:.3g} -> {:.3g}\n\n", step.gap_before, step.gap_after);
    md +=
        "Candidates (gap by screening with the current model's estimator scatter; the best "
        "three of each tier (held terms first, then refits) assessed exactly):\n\n| candidate | "
        "other terms | gap | assessed |\n"
        "|---|---|---|---|\n";
    for (const auto& candidate : step.candidates) {
      md += fmt::format("| {} | {} | {} | {} |\n", term_type_name(candidate.type),
                        candidate.type == TermType::kNonstationary
                            ? "-"
                            : (candidate.refitted ? "refitted" : "held"),
                        candidate.usable       ? fmt::format("{:.4g}", candidate.gap)
                        : candidate.immaterial ? std::string("immaterial (< min share)")
                                               : std::string("fit failed"),
                        candidate.exact ? "exactly" : "screening");
    }
    md += "\nModel after the step:\n\n" + model_lines(step.after.model) + "\n";
    md += gap_summary(step.after.gap) + ".\n\n";
    md += point_table(measured, step.after) + "\n";
    if (i < plots.steps.size() && !plots.steps[i].empty()) {
      md += fmt::format("![after step {}]({})\n\n", i + 1, plots.steps[i]);
    }
  }
  if (!plots.davar.empty()) {
    md += "## Dynamic Allan deviation\n\n";
    md += fmt::format("![DAVAR]({})\n\n", plots.davar);
  }
  md += "## Final model\n\n";
  if (!result.final_selection.empty()) {
    md += "Final model selection: " + result.final_selection + ".\n\n";
  }
  if (result.final_walk_test.blocks > 0) {
    md += fmt::format(
        "Time-domain rate-random-walk test of the final model ({} block means of {:.4g} s): "
        "likelihood ratio {:.2f} against {:.2f}{}.\n\n",
        result.final_walk_test.blocks, result.final_walk_test.block_s,
        result.final_walk_test.statistic, result.final_walk_test.threshold,
        result.final_walk_test.significant ? " (significant: a rate random walk is missing)" : "");
  }
  md += model_lines(result.final_model()) + "\n";
  const Signature& left = result.final_signature;
  if (!result.consistent && left.found) {
    md += fmt::format(
        "What is left: the measured Allan variance lies {} the final model over tau = {:.4g} .. "
        "{:.4g} s (largest |z| = {:.1f} at {:.4g} s; {}). No vocabulary term fitted there "
        "shrinks the gap enough to be added.\n",
        left.above ? "above" : "below", (*left.tau_range_s)[0], (*left.tau_range_s)[1],
        left.max_abs_z, left.tau_at_max_s, left.shape);
  }
  md += wavelet_section(result);
  return md;
}

}  // namespace stochnav

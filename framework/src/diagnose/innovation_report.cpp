// Report files of `diagnose --run` (diagnose/innovation_report.hpp).

#include "stochnav/diagnose/innovation_report.hpp"

#include <fmt/format.h>

namespace stochnav {
namespace {

nlohmann::json optional_number(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json finding_json(const InnovationFinding& f) {
  return {{"effect", f.effect ? nlohmann::json(*f.effect) : nlohmann::json(nullptr)},
          {"aid", f.aid_type},
          {"components", f.components},
          {"sensor", f.sensor},
          {"time_range_s", f.time_range_s
                               ? nlohmann::json({f.time_range_s->first, f.time_range_s->second})
                               : nlohmann::json(nullptr)},
          {"scale", f.scale},
          {"tau_c_s", optional_number(f.tau_c_s)},
          {"period_s", optional_number(f.period_s)},
          {"evidence", f.evidence}};
}

nlohmann::json aid_json(const AidAnalysis& aid) {
  nlohmann::json components = nlohmann::json::array();
  for (const auto& c : aid.components) {
    components.push_back({{"name", c.name},
                          {"sensor_hint", c.sensor_hint},
                          {"level", c.level},
                          {"level_band", {c.level_lo, c.level_hi}},
                          {"lag1_autocorrelation", c.rho1},
                          {"ljung_box_p", c.ljung_box_p},
                          {"effective_terms", c.effective_terms}});
  }
  nlohmann::json t0 = nlohmann::json::array(), t1 = nlohmann::json::array(),
                 level = nlohmann::json::array(), flag = nlohmann::json::array();
  for (const auto& w : aid.windows) {
    t0.push_back(w.t0_s);
    t1.push_back(w.t1_s);
    level.push_back(w.level);
    flag.push_back(w.flag);
  }
  return {{"aid", aid.aid_index},
          {"type", aid.type},
          {"updates", aid.updates},
          {"update_interval_s", aid.update_interval_s},
          {"components", components},
          {"windows", {{"t0", t0}, {"t1", t1}, {"level", level}, {"flag", flag}}},
          {"reference_level", aid.reference_level}};
}

}  // namespace

nlohmann::json innovation_report_json(const InnovationAnalysis& analysis, const std::string& run,
                                      const InnovationAnalysisOptions& options) {
  nlohmann::json aids = nlohmann::json::array(), findings = nlohmann::json::array();
  for (const auto& aid : analysis.aids) aids.push_back(aid_json(aid));
  for (const auto& f : analysis.findings) findings.push_back(finding_json(f));
  return {{"run", run},
          {"consistent", analysis.consistent},
          {"window_s", options.window_s},
          {"alpha", options.alpha},
          {"aids", aids},
          {"findings", findings}};
}

std::string innovation_report_markdown(const InnovationAnalysis& analysis, const std::string& run,
                                       const InnovationAnalysisOptions& options,
                                       const std::string& plot) {
  std::string md = fmt::format("# Innovation diagnosis of the run {}\n\n", run);
  md += fmt::format(
      "Each innovation component normalised by its predicted standard deviation, u = z / "
      "sqrt(S_ii), should be N(0, 1) and white when the filter's noise model is right. Level = "
      "mean u^2 (1 expected; band from chi2 with the effective number of terms); whiteness by "
      "Ljung-Box; levels over windows of {:.0f} s against the run's median level by an F test "
      "(alpha {}, Bonferroni over windows).\n\n",
      options.window_s, options.alpha);
  md += analysis.consistent ? "**Verdict: consistent** — no missing effect found.\n\n"
                            : "**Verdict: not consistent** — see the findings.\n\n";
  md += "## Findings\n\n";
  if (analysis.findings.empty()) md += "None.\n\n";
  for (const auto& f : analysis.findings) {
    md += fmt::format("- **{}** ({}; sensor: {}){}: {}\n", f.effect ? *f.effect : "overstated",
                      f.aid_type, f.sensor,
                      f.time_range_s ? fmt::format(" over [{:.0f}, {:.0f}) s",
                                                   f.time_range_s->first, f.time_range_s->second)
                                     : std::string(),
                      f.evidence);
  }
  for (const auto& aid : analysis.aids) {
    md += fmt::format("\n## Aid {} ({}): {} updates every {:.3g} s\n\n", aid.aid_index, aid.type,
                      aid.updates, aid.update_interval_s);
    md +=
        "| component | level | band | lag-1 autocorrelation | Ljung-Box p | windows high / low |\n";
    md += "|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < aid.components.size(); ++i) {
      const auto& c = aid.components[i];
      int high = 0, low = 0;
      for (const auto& w : aid.windows) {
        high += w.flag[i] == 1;
        low += w.flag[i] == -1;
      }
      md += fmt::format("| {} | {:.3g} | [{:.3g}, {:.3g}] | {:.3g} | {:.2g} | {} / {} of {} |\n",
                        c.name, c.level, c.level_lo, c.level_hi, c.rho1, c.ljung_box_p, high, low,
                        aid.windows.size());
    }
  }
  if (!plot.empty()) md += fmt::format("\n![innovation levels over time]({})\n", plot);
  return md;
}

}  // namespace stochnav

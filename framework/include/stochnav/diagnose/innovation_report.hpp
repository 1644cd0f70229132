#pragma once
// The report of `stochnav diagnose --run RUN_DIR`: DIR/report.json and DIR/report.md.
//
// report.json:
//   {"run": RUN_DIR, "consistent": bool, "window_s": x, "alpha": a,
//    "aids": [{"aid": index, "type": T, "updates": n, "update_interval_s": dt,
//              "components": [{"name", "sensor_hint", "level", "level_band": [lo, hi],
//                              "lag1_autocorrelation", "ljung_box_p", "effective_terms"}],
//              "windows": {"t0": [...], "t1": [...], "level": [[per component]...],
//                          "flag": [[+1 / 0 / -1 per component]...]},
//              "reference_level": [per component]}],
//    "findings": [{"effect": TYPE | null, "aid": T, "components": [...], "sensor": "...",
//                  "time_range_s": [t0, t1] | null, "scale": s, "tau_c_s": x | null,
//                  "period_s": x | null, "evidence": "..."}]}
// effect uses the vocabulary of DESIGN.md; null means the noise is overstated (conservative).

#include <nlohmann/json.hpp>
#include <string>

#include "stochnav/diagnose/innovation_analysis.hpp"

namespace stochnav {

nlohmann::json innovation_report_json(const InnovationAnalysis& analysis, const std::string& run,
                                      const InnovationAnalysisOptions& options);

/// `plot`: file name of the level-over-time plot beside the report, empty when none.
std::string innovation_report_markdown(const InnovationAnalysis& analysis, const std::string& run,
                                       const InnovationAnalysisOptions& options,
                                       const std::string& plot);

}  // namespace stochnav

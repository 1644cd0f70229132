#pragma once
// `stochnav diagnose --run RUN_DIR --out DIR`: the discrepancy question asked of a filter run
// (diagnose/innovation_analysis.hpp). Writes DIR/report.json, DIR/report.md and
// DIR/innovation_levels.<png|svg> (unless plots are "none"); nothing when it fails.

#include <string>

#include "stochnav/diagnose/innovation_analysis.hpp"

namespace stochnav::cli {

void run_innovation_diagnosis(const std::string& run_dir, const std::string& out_dir,
                              const InnovationAnalysisOptions& options, const std::string& plots);

}  // namespace stochnav::cli

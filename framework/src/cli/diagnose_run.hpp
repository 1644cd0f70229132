#pragma once
// `stochnav diagnose --run RUN_DIR --out DIR`: the discrepancy question asked of a filter run
// (diagnose/innovation_analysis.hpp). Writes DIR/report.json, DIR/report.md and
// DIR/innovation_levels.<png|svg> (unless plots are "none"); nothing when it fails.

#include <string>
#include <vector>

#include "stochnav/diagnose/innovation_analysis.hpp"

namespace stochnav::cli {

/// aux_columns: columns of aux_file (default RUN_DIR/aids.csv) tested as channels the
/// innovations may drift with (diagnose/innovation_aux.hpp); report.json gets "aux_drift".
void run_innovation_diagnosis(const std::string& run_dir, const std::string& out_dir,
                              const InnovationAnalysisOptions& options, const std::string& plots,
                              const std::vector<std::string>& aux_columns = {},
                              const std::string& aux_file = {});

}  // namespace stochnav::cli

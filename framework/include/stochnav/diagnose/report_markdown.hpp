#pragma once
// DIR/report.md of `stochnav diagnose`: a readable account of every step with its evidence,
// the gap's definition, the measured and model statistics, and links to the plots.

#include <string>
#include <vector>

#include "stochnav/diagnose/diagnose.hpp"

namespace stochnav {

/// File names (relative to the report's folder) of the plots written beside report.md.
struct DiagnosePlotFiles {
  std::string initial;             ///< measured vs initial model
  std::vector<std::string> steps;  ///< measured vs the model after each step
  std::string davar;               ///< DAVAR plot, empty when not drawn
};

/// `source` names the record (file and column), `model_source` the model file.
std::string diagnose_report_markdown(const DiagnoseResult& result, const std::string& source,
                                     const std::string& model_source,
                                     const DiagnosePlotFiles& plots);

}  // namespace stochnav

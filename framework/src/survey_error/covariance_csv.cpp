#include "stochnav/survey_error/covariance_csv.hpp"

#include <fmt/format.h>

namespace stochnav::survey_error {
namespace {

/// One row; `+ 0.0` turns a negative zero into "0".
void append_covariance_row(std::string& out, double md_m, const std::string& source,
                           const Eigen::Matrix3d& c) {
  fmt::format_to(std::back_inserter(out), "{},{},{},{},{},{},{},{}\n", md_m + 0.0, source,
                 c(0, 0) + 0.0, c(1, 1) + 0.0, c(2, 2) + 0.0, c(0, 1) + 0.0, c(0, 2) + 0.0,
                 c(1, 2) + 0.0);
}

}  // namespace

std::string covariance_csv(const SurveyCovariance& covariance) {
  std::string out = std::string(kCovarianceCsvHeader) + "\n";
  for (std::size_t k = 0; k < covariance.md_m.size(); ++k) {
    for (const SourceCovariance& source : covariance.sources) {
      append_covariance_row(out, covariance.md_m[k], source.code, source.nev_m2[k]);
    }
    append_covariance_row(out, covariance.md_m[k], kTotalSourceName, covariance.total_nev_m2[k]);
  }
  return out;
}

}  // namespace stochnav::survey_error

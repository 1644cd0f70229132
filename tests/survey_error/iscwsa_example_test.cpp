// Validation: the ISCWSA MWD Rev5.11 and Rev4 models on ISCWSA example well #1 reproduce the
// example workbooks' covariances of every error source and the total at MD 1200, 2100, 5100 and
// 8000 m, element by element, at welleng's tolerances. Prints the largest relative error per
// source (docs/survey-error-model.md, Validation).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <string>

#include "iscwsa_reference.hpp"
#include "stochnav/core/angles.hpp"
#include "stochnav/survey_error/error_model.hpp"
#include "stochnav/survey_error/error_propagation.hpp"
#include "temp_dir.hpp"

namespace stochnav::survey_error {
namespace {

using testing::IscwsaReference;

/// The example well as the library takes it.
struct ExampleWell {
  std::vector<ListingStation> stations;
  WellParameters well;
};

ExampleWell example_well(const IscwsaReference& reference) {
  ExampleWell example;
  for (std::size_t k = 0; k < reference.md_m.size(); ++k) {
    example.stations.push_back({reference.md_m[k], reference.inclination_deg[k] * kRadPerDeg,
                                reference.azimuth_deg[k] * kRadPerDeg});
  }
  const auto& h = reference.header;
  example.well.latitude_rad = h.latitude_deg * kRadPerDeg;
  example.well.b_total_nT = h.b_total_nT;
  example.well.dip_rad = h.dip_rad;
  example.well.declination_rad = h.declination_rad;
  example.well.convergence_rad = h.convergence_rad;
  example.well.gravity_m_s2 = h.gravity_m_s2;
  example.well.vertical_inc_limit_rad = h.vertical_inc_limit_rad;
  example.well.azimuth_reference =
      h.azimuth_reference == "grid" ? AzimuthReference::kGrid : AzimuthReference::kTrue;
  return example;
}

/// The worst agreement of one source over its reference rows.
struct SourceAgreement {
  double max_relative = 0.0;  ///< over elements with a non-zero reference
  /// Over elements well above the reference's rounding (|reference| > 1000 atol): the Rev4
  /// reference has 4 decimals, so its small elements have large relative errors by rounding.
  double max_relative_large = 0.0;
  double max_absolute = 0.0;
  int failures = 0;
};

void check_model_against_reference(const std::string& model_name,
                                   const IscwsaReference& reference) {
  const SurveyErrorModel& model = survey_error_model(model_name);
  const ExampleWell example = example_well(reference);
  const SurveyCovariance covariance =
      propagate_survey_errors(model, example.stations, example.well);

  std::map<std::string, const std::vector<Eigen::Matrix3d>*> by_source;
  for (const auto& source : covariance.sources) by_source[source.code] = &source.nev_m2;
  by_source["TOTAL"] = &covariance.total_nev_m2;
  // Every model source has reference rows, and every reference source is in the model.
  std::map<std::string, SourceAgreement> agreement;
  for (const auto& row : reference.rows) {
    ASSERT_TRUE(by_source.count(row.source)) << model_name << " has no source " << row.source;
    const auto station = std::find(covariance.md_m.begin(), covariance.md_m.end(), row.md_m);
    ASSERT_NE(station, covariance.md_m.end()) << "no station at MD " << row.md_m;
    const Eigen::Matrix3d& c =
        (*by_source[row.source])[static_cast<std::size_t>(station - covariance.md_m.begin())];
    const double computed[6] = {c(0, 0), c(1, 1), c(2, 2), c(0, 1), c(0, 2), c(1, 2)};
    const double expected[6] = {row.nn, row.ee, row.vv, row.ne, row.nv, row.ev};
    const char* names[6] = {"nn", "ee", "vv", "ne", "nv", "ev"};
    SourceAgreement& a = agreement[row.source];
    for (int i = 0; i < 6; ++i) {
      const double error = std::abs(computed[i] - expected[i]);
      a.max_absolute = std::max(a.max_absolute, error);
      if (expected[i] != 0.0) {
        a.max_relative = std::max(a.max_relative, error / std::abs(expected[i]));
      }
      if (std::abs(expected[i]) > 1000.0 * reference.atol) {
        a.max_relative_large = std::max(a.max_relative_large, error / std::abs(expected[i]));
      }
      if (!reference.passes(computed[i], expected[i])) {
        ++a.failures;
        ADD_FAILURE() << model_name << " " << row.source << " at MD " << row.md_m << " " << names[i]
                      << ": computed " << computed[i] << ", expected " << expected[i];
      }
    }
  }
  EXPECT_EQ(agreement.size(), model.sources.size() + 1) << "sources compared (with TOTAL)";
  std::cout << model.title << " vs the ISCWSA example workbook (atol " << reference.atol
            << ", rtol " << reference.rtol << "):\n| source | largest relative error | the same "
            << "where abs(reference) > 1000 atol | largest absolute error (m^2) |\n"
            << "|---|---|---|---|\n";
  const auto print_row = [&](const std::string& code) {
    const SourceAgreement& a = agreement[code];
    std::cout << "| " << code << " | " << a.max_relative << " | " << a.max_relative_large << " | "
              << a.max_absolute << " |\n";
  };
  for (const auto& source : model.sources) print_row(source.code);
  print_row("TOTAL");
}

TEST(IscwsaExampleWell, MwdRev5ReproducesTheWorkbookForEverySourceAndTheTotal) {
  STOCHNAV_REQUIRE_SHARED_DATA(path, testing::kIscwsaRev5File);
  check_model_against_reference("mwd_rev5", testing::read_iscwsa_reference(path, 1e-6, 5e-5));
}

TEST(IscwsaExampleWell, MwdRev4ReproducesTheWorkbookForEverySourceAndTheTotal) {
  STOCHNAV_REQUIRE_SHARED_DATA(path, testing::kIscwsaRev4File);
  check_model_against_reference("mwd_rev4", testing::read_iscwsa_reference(path, 5e-5, 1e-3));
}

}  // namespace
}  // namespace stochnav::survey_error

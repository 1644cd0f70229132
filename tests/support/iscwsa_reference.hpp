#pragma once
// ISCWSA example well #1 and its expected covariances (../shared/data/iscwsa/, SOURCES.md
// there): error_mwdrev5_1_iscwsa_data.json (Rev5.11) and error_mwdrev4_1_iscwsa_data.json (Rev4),
// extracted by welleng from the ISCWSA example workbooks. welleng's pass rule per covariance
// element: |error| <= atol or |error| / |reference| <= rtol.

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace stochnav::testing {

/// The well's header as the reference file gives it (dip, declination, convergence and the
/// vertical limit in radians, latitude in degrees).
struct IscwsaReferenceHeader {
  double latitude_deg = 0.0;
  double b_total_nT = 0.0;
  double dip_rad = 0.0;
  double declination_rad = 0.0;
  double convergence_rad = 0.0;
  double gravity_m_s2 = 0.0;
  double vertical_inc_limit_rad = 0.0;
  std::string azimuth_reference;
};

/// One expected row: the six NEV covariance elements of a source (or "TOTAL") at an MD.
struct IscwsaReferenceRow {
  double md_m = 0.0;
  std::string source;
  double nn = 0.0, ee = 0.0, vv = 0.0, ne = 0.0, nv = 0.0, ev = 0.0;
};

struct IscwsaReference {
  IscwsaReferenceHeader header;
  std::vector<double> md_m, inclination_deg, azimuth_deg;
  std::vector<IscwsaReferenceRow> rows;
  double atol = 0.0;
  double rtol = 0.0;

  /// welleng's pass rule for one element.
  bool passes(double computed, double expected) const {
    const double error = std::abs(computed - expected);
    return error <= atol || error <= rtol * std::abs(expected);
  }
};

/// Reads `path`; the Rev4 file's "Totals" rows are renamed "TOTAL". `atol`, `rtol`: the
/// tolerances of the model (Rev5.11: 1e-6, 5e-5; Rev4: 5e-5, 1e-3).
inline IscwsaReference read_iscwsa_reference(const std::string& path, double atol, double rtol) {
  std::ifstream in(path);
  const nlohmann::json json = nlohmann::json::parse(in);
  IscwsaReference reference;
  const auto& header = json.at("header");
  reference.header = {header.at("latitude").get<double>(),
                      header.at("b_total").get<double>(),
                      header.at("dip").get<double>(),
                      header.at("declination").get<double>(),
                      header.at("convergence").get<double>(),
                      header.at("G").get<double>(),
                      header.at("vertical_inc_limit").get<double>(),
                      header.at("azi_reference").get<std::string>()};
  const auto& survey = json.at("survey");
  reference.md_m = survey.at("md").get<std::vector<double>>();
  reference.inclination_deg = survey.at("inc").get<std::vector<double>>();
  reference.azimuth_deg = survey.at("azi").get<std::vector<double>>();
  const auto& expected = json.at("vd");
  for (std::size_t i = 0; i < expected.at("md").size(); ++i) {
    IscwsaReferenceRow row;
    row.md_m = expected["md"][i].get<double>();
    row.source = expected["source"][i].get<std::string>();
    if (row.source == "Totals") row.source = "TOTAL";
    row.nn = expected["nn"][i].get<double>();
    row.ee = expected["ee"][i].get<double>();
    row.vv = expected["vv"][i].get<double>();
    row.ne = expected["ne"][i].get<double>();
    row.nv = expected["nv"][i].get<double>();
    row.ev = expected["ev"][i].get<double>();
    reference.rows.push_back(row);
  }
  reference.atol = atol;
  reference.rtol = rtol;
  return reference;
}

inline constexpr char kIscwsaRev5File[] = "iscwsa/error_mwdrev5_1_iscwsa_data.json";
inline constexpr char kIscwsaRev4File[] = "iscwsa/error_mwdrev4_1_iscwsa_data.json";

}  // namespace stochnav::testing

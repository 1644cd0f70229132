#pragma once
// Rows of a Stable32 result table (the layout of ../shared/data/allan/SOURCES.md), shared by
// the stats tests (tests/stats/stable32_reference.hpp) and the CLI tests.

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace stochnav::testing {

/// One data row of a Stable32 result table.
struct Stable32Row {
  std::size_t m = 0;      ///< AF column
  std::string tau_text;   ///< Tau column as printed (5 significant digits)
  std::size_t terms = 0;  ///< # column
  int alpha = 0;          ///< Alpha column (0 in the 4-column MTIE and TIE rms tables)
  double lower = 0.0;     ///< Min Sigma (0 when not computed)
  double deviation = 0.0;
  double upper = 0.0;  ///< Max Sigma (0 when not computed)
};

/// The data rows of a table file: 7 columns (AF, Tau, #, Alpha, Min Sigma, Sigma, Max Sigma)
/// or, for MTIE and TIE rms, 4 (AF, Tau, #, value). Lines starting with '#' and rows of any
/// other shape are skipped. Throws std::runtime_error when the file cannot be read.
inline std::vector<Stable32Row> read_stable32_table_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::vector<Stable32Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line.front() == '#') continue;
    std::istringstream cells(line);
    Stable32Row row;
    double terms = 0.0;  // Theo1 tables print it as 4.9550e+03
    if (!(cells >> row.m >> row.tau_text >> terms)) continue;
    row.terms = static_cast<std::size_t>(std::llround(terms));
    std::vector<double> rest;
    for (double value = 0.0; cells >> value;) rest.push_back(value);
    if (rest.size() == 1) {
      row.deviation = rest[0];
      rows.push_back(row);
    } else if (rest.size() == 4) {
      row.alpha = static_cast<int>(rest[0]);
      row.lower = rest[1];
      row.deviation = rest[2];
      row.upper = rest[3];
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace stochnav::testing

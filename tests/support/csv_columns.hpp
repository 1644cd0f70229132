#pragma once
// Reading a CSV file the CLI under test wrote (errors.csv, survey_errors.csv, ...) into columns
// by header name; "nan" and empty cells become NaN.

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace stochnav::testing {

using CsvColumns = std::map<std::string, std::vector<double>>;

inline CsvColumns read_csv_columns(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> names;
  CsvColumns columns;
  if (std::getline(in, line)) {
    std::stringstream header(line);
    for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  }
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (std::size_t i = 0; i < names.size() && std::getline(row, cell, ','); ++i) {
      columns[names[i]].push_back(cell == "nan" || cell.empty() ? NAN : std::stod(cell));
    }
  }
  return columns;
}

}  // namespace stochnav::testing

#pragma once
// Reading a CSV file the CLI under test wrote (errors.csv, survey_errors.csv, ...) into columns
// by header name; "nan", empty and text cells (survey.csv's station_type) become NaN: read those
// with read_csv_text_column.

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
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
      double value = NAN;
      if (cell != "nan" && !cell.empty()) {
        std::size_t used = 0;
        try {
          value = std::stod(cell, &used);
        } catch (const std::invalid_argument&) {
          used = 0;
        }
        if (used != cell.size()) value = NAN;  // a text cell
      }
      columns[names[i]].push_back(value);
    }
  }
  return columns;
}

/// One column's cells as text (e.g. survey.csv's station_type), one per data row.
inline std::vector<std::string> read_csv_text_column(const std::string& path,
                                                     const std::string& name) {
  std::ifstream in(path);
  std::string line;
  std::size_t index = 0;
  bool found = false;
  if (std::getline(in, line)) {
    std::stringstream header(line);
    for (std::string cell; std::getline(header, cell, ',') && !found; ++index) {
      found = cell == name;
    }
  }
  std::vector<std::string> cells;
  if (!found) return cells;
  --index;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<std::string> row_cells;
    for (std::string cell; std::getline(row, cell, ',');) row_cells.push_back(cell);
    cells.push_back(index < row_cells.size() ? row_cells[index] : std::string());
  }
  return cells;
}

}  // namespace stochnav::testing

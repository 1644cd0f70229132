#include "stochnav/io/csv_table_reader.hpp"

#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/text_cells.hpp"

namespace stochnav {
namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

CsvTableReader::CsvTableReader(const std::string& path, std::span<const std::string_view> columns)
    : lines_(path) {
  std::string_view line;
  while (lines_.next(line)) {
    line = trim(line);
    if (line.empty() || line.front() == '#') continue;
    split_cells(line, ',', cells_);
    for (auto cell : cells_) header_.emplace_back(trim(cell));
    break;
  }
  if (header_.empty()) {
    throw InputError(path + ": empty file; expected a CSV header row naming the columns");
  }
  for (std::string_view name : columns) {
    std::size_t index = 0;
    while (index < header_.size() && header_[index] != name) ++index;
    if (index == header_.size()) {
      throw InputError(path + ":" + std::to_string(lines_.line_number()) + ": no column '" +
                       std::string(name) + "' (columns: " + joined(header_) +
                       "); write the file with that column");
    }
    indices_.push_back(index);
  }
}

bool CsvTableReader::has_column(std::string_view name) const {
  for (const auto& column : header_) {
    if (column == name) return true;
  }
  return false;
}

bool CsvTableReader::next(std::span<double> values) {
  std::string_view line;
  while (lines_.next(line)) {
    if (trim(line).empty() || line.front() == '#') continue;
    split_cells(line, ',', cells_);
    const auto where = [this] {
      return lines_.path() + ":" + std::to_string(lines_.line_number()) + ": ";
    };
    if (cells_.size() != header_.size()) {
      throw InputError(where() + std::to_string(cells_.size()) + " cells for " +
                       std::to_string(header_.size()) + " columns; fix or remove the row");
    }
    for (std::size_t i = 0; i < indices_.size(); ++i) {
      double value = 0.0;
      if (!parse_number(cells_[indices_[i]], value)) {
        throw InputError(where() + "column " + header_[indices_[i]] + " is not a number ('" +
                         std::string(trim(cells_[indices_[i]])) + "'); fix the cell");
      }
      if (!std::isfinite(value)) {
        throw InputError(where() + "column " + header_[indices_[i]] +
                         " is NaN or infinite; fill the gap or cut the record");
      }
      values[i] = value;
    }
    return true;
  }
  return false;
}

}  // namespace stochnav

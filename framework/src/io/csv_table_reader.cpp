#include "stochnav/io/csv_table_reader.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/text_cells.hpp"

namespace stochnav {
namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + echoed_text(name);
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
  slot_of_column_.assign(header_.size(), -1);
  for (std::size_t i = 0; i < indices_.size(); ++i) {
    int& slot = slot_of_column_[indices_[i]];
    if (slot >= 0) plain_rows_ = false;  // a column asked for twice: the general path only
    slot = static_cast<int>(i);
  }
}

std::string CsvTableReader::text_cell(std::string_view column) const {
  std::size_t index = 0;
  while (index < header_.size() && header_[index] != column) ++index;
  if (index == header_.size()) {
    throw InputError(lines_.path() + ": no column '" + std::string(column) +
                     "' (columns: " + joined(header_) + "); write the file with that column");
  }
  std::vector<std::string_view> cells;
  split_cells(row_, ',', cells);
  return index < cells.size() ? std::string(trim(cells[index])) : std::string();
}

bool CsvTableReader::has_column(std::string_view name) const {
  for (const auto& column : header_) {
    if (column == name) return true;
  }
  return false;
}

bool CsvTableReader::parse_plain_row(std::string_view line, std::span<double> values) const {
  const char* cell = line.data();
  const char* const end = line.data() + line.size();
  std::size_t column = 0;
  while (true) {
    const auto* comma = static_cast<const char*>(std::memchr(cell, ',', end - cell));
    const char* cell_end = comma != nullptr ? comma : end;
    if (column >= slot_of_column_.size()) return false;  // more cells than columns
    if (const int slot = slot_of_column_[column]; slot >= 0) {
      double value = 0.0;
      const auto [stop, error] = std::from_chars(cell, cell_end, value);
      if (error != std::errc() || stop != cell_end || !std::isfinite(value)) return false;
      values[static_cast<std::size_t>(slot)] = value;
    }
    ++column;
    if (comma == nullptr) break;
    cell = comma + 1;
  }
  return column == header_.size();
}

bool CsvTableReader::next(std::span<double> values) {
  std::string_view line;
  while (lines_.next(line)) {
    if (trim(line).empty() || line.front() == '#') continue;
    row_ = line;
    if (plain_rows_ && parse_plain_row(line, values)) return true;
    // Anything else (blanks or '+' around a number, a bad cell, a short row) takes the general
    // path, which accepts what parse_number accepts or names the problem.
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
        throw InputError(where() + "column " + echoed_text(header_[indices_[i]]) +
                         " is not a number ('" + echoed_text(trim(cells_[indices_[i]])) +
                         "'); fix the cell");
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

#include <algorithm>
#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/line_reader.hpp"
#include "stochnav/io/text_cells.hpp"
#include "stochnav/plugin/aid_plugin.hpp"

namespace stochnav::plugin {

AidData::AidData(std::string source, std::vector<std::string> names,
                 std::vector<std::vector<double>> columns)
    : source_(std::move(source)), names_(std::move(names)), columns_(std::move(columns)) {
  if (names_.size() != columns_.size()) {
    throw InputError(source_ + ": " + std::to_string(names_.size()) + " column names for " +
                     std::to_string(columns_.size()) + " columns; give one name per column");
  }
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (columns_[i].size() != columns_.front().size()) {
      throw InputError(source_ + ": column '" + names_[i] + "' has " +
                       std::to_string(columns_[i].size()) + " rows, '" + names_.front() + "' has " +
                       std::to_string(columns_.front().size()) +
                       "; give every column the same number of rows");
    }
  }
  if (!has("t")) {
    throw InputError(source_ + ": no time column 't'; add a column 't' with the time in s");
  }
  const auto t = time_s();
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (!(t[i] > t[i - 1])) {
      throw InputError(source_ + ": time t is not increasing at row " + std::to_string(i + 1) +
                       " (t = " + std::to_string(t[i]) + " s); sort the rows by time");
    }
  }
}

bool AidData::has(std::string_view name) const {
  return std::find(names_.begin(), names_.end(), name) != names_.end();
}

std::span<const double> AidData::column(std::string_view name, std::string_view pointer) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) {
    std::string known;
    for (const auto& column_name : names_) known += (known.empty() ? "" : ", ") + column_name;
    throw MissingDataError(std::string(pointer) + ": aid data " +
                      (source_.empty() ? std::string("(none given)") : source_) +
                      " has no column '" + std::string(name) +
                      "'; columns: " + (known.empty() ? std::string("(none)") : known) +
                      " (give the run an aids file with that column)");
  }
  return columns_[static_cast<std::size_t>(it - names_.begin())];
}

std::span<const double> AidData::time_s() const {
  const auto it = std::find(names_.begin(), names_.end(), "t");
  if (it == names_.end()) return {};
  return columns_[static_cast<std::size_t>(it - names_.begin())];
}

std::size_t AidData::rows() const { return columns_.empty() ? 0 : columns_.front().size(); }

void AidData::move_row_time(std::size_t row, double t_s) {
  const auto it = std::find(names_.begin(), names_.end(), "t");
  columns_[static_cast<std::size_t>(it - names_.begin())].at(row) = t_s;
}

AidData read_aid_data(const std::filesystem::path& csv_path) {
  LineReader reader(csv_path.string());
  std::string_view line;
  std::vector<std::string_view> cells;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  const std::string file = csv_path.string();
  while (reader.next(line)) {
    if (trim(line).empty() || trim(line).front() == '#') continue;
    split_cells(line, ',', cells);
    if (names.empty()) {
      for (auto cell : cells) names.emplace_back(trim(cell));
      columns.resize(names.size());
      continue;
    }
    const std::string where = file + ":" + std::to_string(reader.line_number());
    if (cells.size() != names.size()) {
      throw InputError(where + ": " + std::to_string(cells.size()) + " cells, the header has " +
                       std::to_string(names.size()) + "; give every row one cell per column");
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      double value = 0.0;
      if (!parse_number(cells[i], value) || !std::isfinite(value)) {
        throw InputError(where + ": column '" + echoed_text(names[i]) + "': '" +
                         echoed_text(trim(cells[i])) +
                         "' is not a finite number; fix the cell");
      }
      columns[i].push_back(value);
    }
  }
  if (names.empty()) throw InputError(file + ": empty file; expected a CSV header with 't'");
  return AidData(file, std::move(names), std::move(columns));
}

}  // namespace stochnav::plugin

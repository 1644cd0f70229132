#pragma once
// Streams a numeric CSV table with a header row, row by row, picking columns by name: for
// records too long to hold (an IMU file of 200 h at 100 Hz), read once, front to back.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochnav/io/line_reader.hpp"

namespace stochnav {

class CsvTableReader final {
 public:
  /// Opens `path` (plain or .gz) and reads its header, skipping blank and '#' lines before it.
  /// `columns`: the names wanted, in the order next() returns them. Throws InputError naming
  /// the file, line and the columns found when the file is empty or a column is missing.
  CsvTableReader(const std::string& path, std::span<const std::string_view> columns);

  /// Reads the next data row into `values` (one per requested column). Returns false at the
  /// end of the file. Throws InputError "file:line: ..." for a short row, a non-numeric cell
  /// or a NaN / infinite value.
  bool next(std::span<double> values);

  /// The current row's (the last next()'s) cell of `column` as text, trimmed: a text column
  /// beside the numbers (survey.csv's station_type). Throws InputError when the header has no
  /// such column; "" when the row is short.
  std::string text_cell(std::string_view column) const;

  /// Whether the header has this column.
  bool has_column(std::string_view name) const;
  const std::vector<std::string>& header() const { return header_; }
  const std::string& path() const { return lines_.path(); }
  std::size_t line_number() const { return lines_.line_number(); }

 private:
  // The common row (plain numbers between commas, as many cells as columns): one pass with
  // std::from_chars, no splitting. False sends the row to the general path, which accepts
  // exactly what this accepts (with the same values) and more, or throws.
  bool parse_plain_row(std::string_view line, std::span<double> values) const;

  LineReader lines_;
  std::vector<std::string> header_;
  std::vector<std::size_t> indices_;  // header index of each requested column
  std::vector<int> slot_of_column_;   // per header column: its place in next()'s values, or -1
  bool plain_rows_ = true;            // parse_plain_row usable (no column requested twice)
  std::vector<std::string_view> cells_;
  std::string_view row_;  // the current row (valid until the next read)
};

}  // namespace stochnav

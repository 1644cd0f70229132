#include "stochnav/io/record.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/line_reader.hpp"
#include "stochnav/io/sample_reader.hpp"
#include "stochnav/io/text_cells.hpp"

namespace stochnav {

Record read_record(const ReadOptions& options) { return read_record(options, 0); }

Record describe_record(const ReadOptions& options, const SampleReader& reader) {
  Record record;
  record.rate_hz = reader.rate_hz();
  record.start_time_s = reader.start_time_s();
  record.kind = options.kind;
  record.unit = options.unit;
  record.source = options.path;
  record.column = reader.column_name();
  return record;
}

Record read_record(const ReadOptions& options, std::size_t leading_zeros) {
  SampleReader reader(options);
  std::vector<double> values(leading_zeros, 0.0);
  reader.read_all(values);
  Record record = describe_record(options, reader);
  record.values = std::move(values);
  return record;
}

std::vector<std::string> list_columns(const std::string& path) {
  LineReader lines(path);
  std::string_view line;
  std::vector<std::string_view> cells;
  while (lines.next(line)) {
    line = trim(line);
    if (line.empty() || line.front() == '#') continue;
    split_cells(line, line.find(',') != std::string_view::npos ? ',' : ' ', cells);
    break;
  }
  std::vector<std::string> names;
  for (auto cell : cells) names.emplace_back(trim(cell));
  return names;
}

}  // namespace stochnav

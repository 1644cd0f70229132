#include "stochnav/io/sample_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>
#include <unordered_map>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/huge_page_buffer.hpp"
#include "stochnav/io/line_reader.hpp"
#include "stochnav/io/mapped_file.hpp"
#include "stochnav/io/text_cells.hpp"
#include "stochnav/stats/parallel.hpp"

namespace stochnav {
namespace {

enum class FileFormat { kCsv, kText, kFloat64, kFloat32 };

FileFormat format_of(std::string_view path) {
  std::string_view stem = path;
  if (stem.ends_with(".gz")) stem.remove_suffix(3);
  if (stem.ends_with(".csv")) return FileFormat::kCsv;
  if (path.ends_with(".f64")) return FileFormat::kFloat64;
  if (path.ends_with(".f32")) return FileFormat::kFloat32;
  return FileFormat::kText;
}

// Samples beyond this magnitude are refused: squared differences of such numbers, summed over a
// record, overflow a double (alternating +/-1e308 gave NaN deviations), and no sensor writes them.
constexpr double kMaxSampleMagnitude = 1e100;

std::string magnitude_problem(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return std::string(text) + " is beyond +/-1e100, where the Allan variance's squared "
         "differences overflow; rescale the record (another --unit, or divide it)";
}

std::string rate_bounds_problem(const std::string& what, double rate_hz) {
  char text[160];
  std::snprintf(text, sizeof text,
                "%s %.6g Hz is outside [%g, %g] Hz, the sampling rates the statistics can "
                "represent; give the rate in Hz (docs/reliability.md, Inputs)",
                what.c_str(), rate_hz, kMinRecordRateHz, kMaxRecordRateHz);
  return text;
}

bool is_time_column(std::string_view name) {
  return name == "t" || name == "t_s" || name == "time" || name == "time_s";
}

std::optional<std::size_t> parse_index(std::string_view text) {
  if (text.empty() || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  std::size_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  // Beyond size_t: no such column either (not column 0, which a failed parse would leave).
  if (error != std::errc() || end != text.data() + text.size()) {
    return std::numeric_limits<std::size_t>::max();
  }
  return value;
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + echoed_text(name);
  return out;
}

/// A header cell as a column name: a name in double quotes (RFC 4180) without them, a doubled
/// quote inside as one.
std::string header_name(std::string_view cell) {
  if (cell.size() < 2 || cell.front() != '"' || cell.back() != '"') return std::string(cell);
  std::string name;
  const std::string_view inner = cell.substr(1, cell.size() - 2);
  for (std::size_t i = 0; i < inner.size(); ++i) {
    name += inner[i];
    if (inner[i] == '"' && i + 1 < inner.size() && inner[i + 1] == '"') ++i;
  }
  return name;
}

/// The message after "path:line" for a cell that is not a number.
std::string not_a_number_problem(std::string_view cell, const std::string& column) {
  if (cell.find('\0') != std::string_view::npos) {
    return ": a NUL byte in column '" + echoed_text(column) +
           "': the file holds binary data, not text; give a CSV or text record (raw samples: "
           ".f64 or .f32)";
  }
  return ": '" + echoed_text(cell) + "' in column '" + echoed_text(column) +
         "' is not a number; fix or remove the row";
}

}  // namespace

/// Tracks a time column: checks uniform, increasing sampling and derives the rate.
class TimeAxis {
 public:
  void add(double t_s, const std::string& where) {
    if (count_ == 0) {
      first_ = t_s;
    } else if (count_ == 1 && t_s - last_ > 0.0) {
      nominal_step_ = t_s - last_;
    } else if (const std::string problem = step_problem(last_, t_s, nominal_step_);
               !problem.empty()) {
      throw InputError(where + problem);
    }
    last_ = t_s;
    ++count_;
  }

  /// "" when t_s may follow `previous` in a record sampled every `nominal_step` s (0: not yet
  /// known, only an increase is required); otherwise the message after "path:line".
  static std::string step_problem(double previous, double t_s, double nominal_step) {
    const double step = t_s - previous;
    if (!(step > 0.0)) {
      return ": time does not increase (t = " + format(t_s) + " s after " + format(previous) +
             " s); sort the record and remove duplicate epochs";
    }
    if (nominal_step > 0.0 && std::abs(step - nominal_step) > 0.01 * nominal_step) {
      return ": time is not uniformly sampled (step " + format(step) +
             " s where the record started with " + format(nominal_step) +
             " s); fill the gap or split the record at this line";
    }
    return {};
  }

  /// Takes `count` more samples checked elsewhere, the last at `last_s`.
  void extend(std::size_t count, double last_s) {
    if (count == 0) return;
    count_ += count;
    last_ = last_s;
  }
  std::size_t count() const { return count_; }
  double last() const { return last_; }
  double nominal_step() const { return nominal_step_; }
  bool has_rate() const { return count_ >= 2; }
  double rate_hz() const { return static_cast<double>(count_ - 1) / (last_ - first_); }
  double first() const { return first_; }

 private:
  static std::string format(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
  }
  std::size_t count_ = 0;
  double first_ = 0.0;
  double last_ = 0.0;
  double nominal_step_ = 0.0;
};

/// One piece of a text file parsed in parallel (SampleReader::Impl::read_text_in_parallel).
struct TextChunk {
  std::size_t lines = 0;           // lines in the chunk
  std::size_t rows = 0;            // data lines (not blank, not '#')
  std::size_t first_line = 0;      // 1-based number of its first line
  std::size_t first_row = 0;       // index of its first sample in the output
  std::size_t parsed = 0;          // rows parsed before the first problem
  std::size_t first_row_line = 0;  // line of its first parsed row
  double first_t = 0.0;            // time of its first and last parsed rows (s)
  double last_t = 0.0;
  std::size_t problem_line = 0;    // line of the first problem, if any
  std::string problem;             // its message after "path:line"; empty if none
};

bool is_data_line(std::string_view line) {
  const std::string_view trimmed = trim(line);
  return !trimmed.empty() && trimmed.front() != '#';
}

/// Calls visit(line) for each line (terminator and a trailing '\r' removed) until it returns
/// false.
template <typename Visit>
void for_each_line(std::string_view text, const Visit& visit) {
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(at, end - at);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!visit(line)) return;
    at = end + 1;
  }
}

class SampleReader::Impl {
 public:
  explicit Impl(const ReadOptions& options) : options_(options), format_(format_of(options.path)) {
    if (options.rate_hz && !(*options.rate_hz > 0.0 && std::isfinite(*options.rate_hz))) {
      throw ConfigError("--rate must be a positive number of Hz (got " +
                        std::to_string(*options.rate_hz) + ")");
    }
    if (options.rate_hz && !(*options.rate_hz >= kMinRecordRateHz &&
                             *options.rate_hz <= kMaxRecordRateHz)) {
      throw ConfigError(rate_bounds_problem("--rate", *options.rate_hz));
    }
    if (format_ == FileFormat::kFloat64 || format_ == FileFormat::kFloat32) {
      open_binary();
    } else {
      lines_.emplace(options.path);
      open_text();
    }
    if (!time_column_ && !options.rate_hz) {
      throw ConfigError(options.path + ": no time column (t, t_s, time) and no --rate; give --rate HZ");
    }
  }

  std::size_t read_block(std::vector<double>& out, std::size_t max_samples) {
    const std::size_t got = binary_ ? read_binary(out, max_samples) : read_text(out, max_samples);
    note_progress(binary_ ? epochs_read_ * channels_ * sample_bytes_ : lines_->consumed_bytes());
    samples_ += got;
    note_peak(out, got);
    if (got == 0 && !finished_) finish();
    return got;
  }

  std::size_t read_all(std::vector<double>& out) {
    std::size_t got = 0;
    if (!binary_ && lines_->plain() && !text_exhausted_) {
      // Two samples the usual way fix the time step the chunks check against.
      got = read_text(out, 2);
      samples_ += got;
      const std::size_t rest = read_text_in_parallel(out);
      samples_ += rest;
      got += rest;
      note_peak(out, got);
    }
    while (const std::size_t block = read_block(out, std::size_t{1} << 22)) got += block;
    return got;
  }

  double rate_hz() const {
    if (time_column_ && time_.has_rate()) return time_.rate_hz();
    return options_.rate_hz.value_or(0.0);
  }
  double start_time_s() const { return time_column_ ? time_.first() : 0.0; }
  const std::string& column_name() const { return column_name_; }
  std::size_t samples_read() const { return samples_; }

 private:
  std::string where() const { return options_.path + ":" + std::to_string(lines_->line_number()); }

  // Adds the bytes consumed since the last call to the caller's progress counter, if any.
  void note_progress(std::size_t position) {
    if (options_.bytes_read == nullptr || position <= reported_bytes_) return;
    options_.bytes_read->fetch_add(position - reported_bytes_, std::memory_order_relaxed);
    reported_bytes_ = position;
  }

  // Skips blank and '#' lines. Returns false at the end of the file.
  bool next_data_line(std::string_view& line) {
    while (lines_->next(line)) {
      const std::string_view trimmed = trim(line);
      if (trimmed.empty() || trimmed.front() == '#') continue;
      line = trimmed;
      return true;
    }
    return false;
  }

  void open_text() {
    separator_ = format_ == FileFormat::kCsv ? ',' : ' ';
    std::string_view first;
    if (!next_data_line(first)) {
      throw InputError(options_.path + ": no samples (the file is empty or only comments); " +
                       "check that --input names the record");
    }
    split_cells(first, separator_, cells_);
    const bool numeric_first_line = std::all_of(cells_.begin(), cells_.end(), [](std::string_view c) {
      double ignored = 0.0;
      return parse_number(c, ignored);
    });
    if (format_ == FileFormat::kCsv && !numeric_first_line) {
      for (auto cell : cells_) names_.push_back(header_name(trim(cell)));
      refuse_duplicate_names();
    } else {
      for (std::size_t i = 0; i < cells_.size(); ++i) names_.push_back(std::to_string(i));
      pending_line_ = std::string(first);  // the first line is data
    }
    choose_columns();
  }

  // Two columns of one name: which one --column (or the time column) means is a guess. Empty
  // names (a trailing comma) name no column and may repeat.
  void refuse_duplicate_names() const {
    std::unordered_map<std::string_view, std::size_t> first_of;
    for (std::size_t j = 0; j < names_.size(); ++j) {
      if (names_[j].empty()) continue;
      const auto [at, inserted] = first_of.emplace(names_[j], j);
      if (inserted) continue;
      throw InputError(options_.path + ":" + std::to_string(lines_->line_number()) +
                       ": the header names column '" + echoed_text(names_[j]) +
                       "' twice (columns " + std::to_string(at->second) + " and " +
                       std::to_string(j) + "); give each column its own name");
    }
  }

  void choose_columns() {
    for (std::size_t i = 0; i < names_.size(); ++i) {
      if (is_time_column(names_[i])) time_column_ = i;
    }
    if (options_.column.empty()) {
      for (std::size_t i = 0; i < names_.size(); ++i) {
        if (!time_column_ || i != *time_column_) {
          value_column_ = i;
          break;
        }
      }
      if (!value_column_) {
        throw InputError(options_.path + ":1: only a time column; the record needs a data column");
      }
    } else if (auto index = parse_index(options_.column)) {
      if (*index >= names_.size()) {
        throw InputError(options_.path + ":1: column index " + echoed_text(options_.column) +
                         " out of range (" +
                         std::to_string(names_.size()) + " columns: " + join(names_) +
                         "); pass --column with an index from 0 to " +
                         std::to_string(names_.size() - 1));
      }
      value_column_ = *index;
    } else {
      const auto it = std::find(names_.begin(), names_.end(), options_.column);
      if (it == names_.end()) {
        throw InputError(options_.path + ":1: no column '" + echoed_text(options_.column) +
                         "' (columns: " +
                         join(names_) + "); pass --column with one of these names or an index");
      }
      value_column_ = static_cast<std::size_t>(it - names_.begin());
    }
    if (time_column_ && *time_column_ == *value_column_) time_column_.reset();
    column_name_ = names_[*value_column_];
  }

  /// One data line: its value (and time, if the record has a time column) or, on failure,
  /// the message after "path:line". No shared state: safe on several threads at once.
  struct Row {
    double value = 0.0;
    double t_s = 0.0;
    std::string problem;
  };
  void parse_row(std::string_view line, std::vector<std::string_view>& cells, Row& row) const {
    split_cells(line, separator_, cells);
    if (cells.size() != names_.size() && format_ == FileFormat::kCsv) {
      row.problem = ": row has " + std::to_string(cells.size()) + " cells, the header " +
                    std::to_string(names_.size()) + "; fix the row or remove it";
      return;
    }
    if (*value_column_ >= cells.size()) {
      row.problem = ": row has no column " + std::to_string(*value_column_) +
                    "; fix the row or choose another --column";
      return;
    }
    const std::string_view cell = cells[*value_column_];
    if (!parse_number(cell, row.value)) {
      row.problem = not_a_number_problem(trim(cell), column_name_);
      return;
    }
    if (!std::isfinite(row.value)) {
      row.problem = ": " + echoed_text(trim(cell)) + " in column '" + echoed_text(column_name_) +
                    "'; NaN and infinity are not samples: fill the gap or split the record";
      return;
    }
    if (std::abs(row.value) > kMaxSampleMagnitude) {
      row.problem = ": column '" + echoed_text(column_name_) + "': " + magnitude_problem(row.value);
      return;
    }
    if (time_column_) {
      const std::string_view t_cell = cells[*time_column_];
      if (!parse_number(t_cell, row.t_s) || !std::isfinite(row.t_s)) {
        row.problem = ": time '" + echoed_text(trim(t_cell)) +
                      "' is not a finite number; fix or remove the row";
      }
    }
  }

  void parse_line(std::string_view line, std::vector<double>& out) {
    Row row;
    parse_row(line, cells_, row);
    if (!row.problem.empty()) throw InputError(where() + row.problem);
    if (time_column_) time_.add(row.t_s, where());
    out.push_back(row.value);
  }

  std::size_t read_text(std::vector<double>& out, std::size_t max_samples) {
    std::size_t got = 0;
    if (text_exhausted_) return 0;
    if (pending_line_ && max_samples > 0) {
      parse_line(*pending_line_, out);
      pending_line_.reset();
      ++got;
    }
    std::string_view line;
    while (got < max_samples && next_data_line(line)) {
      parse_line(line, out);
      ++got;
    }
    return got;
  }

  /// The rest of a plain text file, in parallel chunks of the memory-mapped file. Returns the
  /// samples appended; the line reader is not used again.
  std::size_t read_text_in_parallel(std::vector<double>& out) {
    const MappedFile file(options_.path);
    const std::string_view text(reinterpret_cast<const char*>(file.bytes().data()),
                                file.bytes().size());
    const std::size_t begin = std::min(lines_->consumed_bytes(), text.size());
    // Chunk boundaries: every kChunkBytes, moved on to the next line start. They depend on the
    // file alone, so the split does not depend on the thread count.
    constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
    std::vector<std::size_t> starts{begin};
    for (std::size_t at = begin + kChunkBytes; at < text.size();) {
      const std::size_t newline = text.find('\n', at);
      if (newline == std::string_view::npos || newline + 1 >= text.size()) break;
      starts.push_back(newline + 1);
      at = newline + 1 + kChunkBytes;
    }
    starts.push_back(text.size());
    const std::size_t chunks = starts.size() - 1;
    const auto chunk_text = [&](std::size_t c) {
      return text.substr(starts[c], starts[c + 1] - starts[c]);
    };

    // Pass 1: lines and data rows per chunk, hence each chunk's first line number and its
    // place in `out`, which then grows once.
    std::vector<TextChunk> info(chunks);
    parallel_for(chunks, [&](std::size_t c) {
      for_each_line(chunk_text(c), [&](std::string_view line) {
        ++info[c].lines;
        if (is_data_line(line)) ++info[c].rows;
        return true;
      });
      // Each pass lets go of a chunk's pages once done: the mapped text never sits in memory
      // whole beside the samples.
      file.release(starts[c], starts[c + 1] - starts[c]);
    });
    const std::size_t before = out.size();
    std::size_t rows = 0;
    std::size_t line = lines_->line_number() + 1;
    for (auto& chunk : info) {
      chunk.first_line = line;
      chunk.first_row = before + rows;
      line += chunk.lines;
      rows += chunk.rows;
    }
    if (out.capacity() < before + rows) {
      std::vector<double> whole = huge_page_buffer(before + rows);
      whole.assign(out.begin(), out.end());
      out.swap(whole);
    }
    out.resize(before + rows);

    // Pass 2: every chunk parsed straight into its place; a chunk stops at its first problem.
    const double nominal_step = time_.nominal_step();
    parallel_for(chunks, [&](std::size_t c) {
      TextChunk& chunk = info[c];
      std::vector<std::string_view> cells;
      Row row;
      std::size_t line_number = chunk.first_line;
      double* into = out.data() + chunk.first_row;
      for_each_line(chunk_text(c), [&](std::string_view text_line) {
        const std::size_t this_line = line_number++;
        if (!is_data_line(text_line)) return true;
        parse_row(trim(text_line), cells, row);
        if (row.problem.empty() && time_column_ && chunk.parsed > 0) {
          row.problem = TimeAxis::step_problem(chunk.last_t, row.t_s, nominal_step);
        }
        if (!row.problem.empty()) {
          chunk.problem_line = this_line;
          chunk.problem = std::move(row.problem);
          return false;
        }
        if (chunk.parsed == 0) {
          chunk.first_t = row.t_s;
          chunk.first_row_line = this_line;
        }
        chunk.last_t = row.t_s;
        into[chunk.parsed++] = row.value;
        return true;
      });
      file.release(starts[c], starts[c + 1] - starts[c]);
      if (options_.bytes_read != nullptr) {
        options_.bytes_read->fetch_add(starts[c + 1] - starts[c], std::memory_order_relaxed);
      }
    });
    reported_bytes_ = text.size();

    // The first problem in file order: inside a chunk, or between the last row of one chunk and
    // the first of the next (checked here, in order, as the serial reader would).
    bool have_previous = time_.count() > 0;
    double previous_t = time_.last();
    std::size_t appended = 0;
    for (const TextChunk& chunk : info) {
      if (time_column_ && have_previous && chunk.parsed > 0) {
        const std::string problem = TimeAxis::step_problem(previous_t, chunk.first_t, nominal_step);
        if (!problem.empty()) {
          throw InputError(options_.path + ":" + std::to_string(chunk.first_row_line) + problem);
        }
      }
      if (!chunk.problem.empty()) {
        throw InputError(options_.path + ":" + std::to_string(chunk.problem_line) + chunk.problem);
      }
      if (chunk.parsed > 0) {
        if (time_column_) time_.extend(chunk.parsed, chunk.last_t);
        have_previous = true;
        previous_t = chunk.last_t;
      }
      appended += chunk.parsed;
    }
    text_exhausted_ = true;
    return appended;
  }

  void open_binary() {
    refuse_folder(options_.path);
    binary_ = std::make_unique<std::ifstream>(options_.path, std::ios::binary | std::ios::ate);
    if (!*binary_) {
      throw InputError(options_.path + ": cannot open file (" + std::strerror(errno) +
                       "); check the path given with --input");
    }
    const auto bytes = static_cast<std::size_t>(binary_->tellg());
    binary_->seekg(0);
    sample_bytes_ = format_ == FileFormat::kFloat64 ? 8 : 4;
    if (options_.binary_channels < 1) {
      throw ConfigError("--columns must be at least 1 (got " +
                        std::to_string(options_.binary_channels) + ")");
    }
    channels_ = static_cast<std::size_t>(options_.binary_channels);
    const std::size_t epoch_bytes = sample_bytes_ * channels_;
    if (bytes % epoch_bytes != 0) {
      throw InputError(options_.path + ": size " + std::to_string(bytes) +
                       " bytes is not a whole number of epochs of " + std::to_string(channels_) +
                       " x " + std::to_string(sample_bytes_) + " bytes; check --columns and the type");
    }
    epochs_total_ = bytes / epoch_bytes;
    for (std::size_t i = 0; i < channels_; ++i) names_.push_back(std::to_string(i));
    choose_columns();
    time_column_.reset();
  }

  std::size_t read_binary(std::vector<double>& out, std::size_t max_samples) {
    const std::size_t epochs = std::min(max_samples, epochs_total_ - epochs_read_);
    if (sample_bytes_ == 8 && channels_ == 1) return read_float64_column(out, epochs);
    raw_.resize(epochs * channels_ * sample_bytes_);
    binary_->read(raw_.data(), static_cast<std::streamsize>(raw_.size()));
    for (std::size_t e = 0; e < epochs; ++e) {
      const char* at = raw_.data() + (e * channels_ + *value_column_) * sample_bytes_;
      double value = 0.0;
      if (sample_bytes_ == 8) {
        std::memcpy(&value, at, 8);
      } else {
        float narrow = 0.0F;
        std::memcpy(&narrow, at, 4);
        value = narrow;
      }
      if (!std::isfinite(value)) {
        throw InputError(options_.path + ": epoch " + std::to_string(epochs_read_ + e) +
                         " of channel " + column_name_ +
                         " is NaN or infinite; fill the gap or split the record");
      }
      if (std::abs(value) > kMaxSampleMagnitude) {
        throw InputError(options_.path + ": epoch " + std::to_string(epochs_read_ + e) +
                         " of channel " + column_name_ + ": " + magnitude_problem(value));
      }
      out.push_back(value);
    }
    epochs_read_ += epochs;
    return epochs;
  }

  // The common case, one float64 channel: read straight into `out`, then check in bulk.
  std::size_t read_float64_column(std::vector<double>& out, std::size_t epochs) {
    const std::size_t first = out.size();
    if (out.capacity() < first + epochs) {
      // The whole remaining file at once, in huge pages: no regrowth copies, few page faults.
      std::vector<double> whole = huge_page_buffer(first + (epochs_total_ - epochs_read_));
      whole.assign(out.begin(), out.end());
      out.swap(whole);
    }
    out.resize(first + epochs);
    binary_->read(reinterpret_cast<char*>(out.data() + first),
                  static_cast<std::streamsize>(epochs * sizeof(double)));
    // x - x is 0 for every finite x and NaN otherwise; the sum vectorizes.
    // The largest magnitude, for the same reason; NaN makes the comparison false, not larger.
    double poison = 0.0;
    double peak = 0.0;
    for (std::size_t i = first; i < out.size(); ++i) {
      poison += out[i] - out[i];
      peak = std::max(peak, std::abs(out[i]));
    }
    if (poison != 0.0 || std::isnan(poison) || peak > kMaxSampleMagnitude) {
      for (std::size_t i = first; i < out.size(); ++i) {
        if (!std::isfinite(out[i])) {
          throw InputError(options_.path + ": epoch " + std::to_string(epochs_read_ + i - first) +
                           " of channel " + column_name_ +
                           " is NaN or infinite; fill the gap or split the record");
        }
        if (std::abs(out[i]) > kMaxSampleMagnitude) {
          throw InputError(options_.path + ": epoch " + std::to_string(epochs_read_ + i - first) +
                           " of channel " + column_name_ + ": " + magnitude_problem(out[i]));
        }
      }
    }
    epochs_read_ += epochs;
    return epochs;
  }

  // The largest |sample| of the last `count` samples appended to `out`.
  void note_peak(const std::vector<double>& out, std::size_t count) {
    for (std::size_t i = out.size() - count; i < out.size(); ++i) {
      peak_ = std::max(peak_, std::abs(out[i]));
    }
  }

  void finish() {
    finished_ = true;
    if (samples_ == 0) {
      throw InputError(options_.path + ": no samples (the file is empty or only comments); " +
                       "check that --input names the record");
    }
    if (samples_ < 2) {
      throw InputError(options_.path + ": only one sample; an Allan variance needs at least two");
    }
    // Samples all tiny: their squared differences underflow (1e-170 gave deviations of 0).
    if (peak_ > 0.0 && peak_ < kMinRecordPeakMagnitude) {
      char text[64];
      std::snprintf(text, sizeof text, "%.6g", peak_);
      throw InputError(options_.path + ": the largest sample magnitude is " + text +
                       ", below 1e-100, where the Allan variance's squared differences "
                       "underflow; rescale the record (another --unit, or multiply it)");
    }
    if (time_column_ && time_.has_rate() &&
        !(time_.rate_hz() >= kMinRecordRateHz && time_.rate_hz() <= kMaxRecordRateHz)) {
      throw InputError(options_.path + ": " + rate_bounds_problem("the time column's rate",
                                                                  time_.rate_hz()));
    }
    if (time_column_ && options_.rate_hz &&
        std::abs(time_.rate_hz() - *options_.rate_hz) > 1e-4 * *options_.rate_hz) {
      throw InputError(options_.path + ": --rate " + std::to_string(*options_.rate_hz) +
                       " Hz disagrees with the time column (" + std::to_string(time_.rate_hz()) +
                       " Hz); drop --rate or fix the time column");
    }
  }

  ReadOptions options_;
  FileFormat format_;
  std::optional<LineReader> lines_;
  std::unique_ptr<std::ifstream> binary_;
  std::vector<char> raw_;
  std::size_t sample_bytes_ = 8;
  std::size_t channels_ = 1;
  std::size_t epochs_total_ = 0;
  std::size_t epochs_read_ = 0;
  char separator_ = ',';
  std::vector<std::string> names_;
  std::vector<std::string_view> cells_;
  std::optional<std::string> pending_line_;
  std::optional<std::size_t> value_column_;
  std::optional<std::size_t> time_column_;
  std::string column_name_;
  TimeAxis time_;
  std::size_t samples_ = 0;
  std::size_t reported_bytes_ = 0;  // bytes added to options_.bytes_read so far
  double peak_ = 0.0;  // the largest |sample| so far
  bool finished_ = false;
  bool text_exhausted_ = false;  // read_text_in_parallel took the rest of the file
};

SampleReader::SampleReader(const ReadOptions& options) : impl_(std::make_unique<Impl>(options)) {}
SampleReader::~SampleReader() = default;
std::size_t SampleReader::read_all(std::vector<double>& out) { return impl_->read_all(out); }
std::size_t SampleReader::read_block(std::vector<double>& out, std::size_t max_samples) {
  return impl_->read_block(out, max_samples);
}
double SampleReader::rate_hz() const { return impl_->rate_hz(); }
double SampleReader::start_time_s() const { return impl_->start_time_s(); }
const std::string& SampleReader::column_name() const { return impl_->column_name(); }
std::size_t SampleReader::samples_read() const { return impl_->samples_read(); }

}  // namespace stochnav

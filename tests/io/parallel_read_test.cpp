// Whole-file reading: the parallel CSV/text parser against the serial streaming reader, and the
// memory-mapped raw float64 path of read_phase_record.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/mapped_file.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/io/sample_reader.hpp"
#include "stochnav/stats/parallel.hpp"
#include "stochnav/stats/phase.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::TempDir;

/// Restores the default thread count when a test ends.
class ThreadCountGuard {
 public:
  ~ThreadCountGuard() { set_stats_thread_count(0); }
};

/// The serial reader: read_block, block after block.
struct SerialRead {
  std::vector<double> values;
  double rate_hz = 0.0;
  double start_time_s = 0.0;
};
SerialRead read_serially(const ReadOptions& options) {
  SampleReader reader(options);
  SerialRead out;
  while (reader.read_block(out.values, 1000) > 0) {
  }
  out.rate_hz = reader.rate_hz();
  out.start_time_s = reader.start_time_s();
  return out;
}

/// The error message of `read`, or "" if it succeeds.
template <typename Read>
std::string error_of(const Read& read) {
  try {
    read();
  } catch (const InputError& error) {
    return error.what();
  }
  return {};
}

/// Data line of row i at time t_s with cell text `value`.
std::string row_line(double t_s, const std::string& value) {
  char time[32];
  std::snprintf(time, sizeof time, "%010.2f", t_s);
  return std::string(time) + "," + value;
}

/// A CSV of `rows` rows, sampled at 100 Hz, with comment and blank lines every 5000 rows and
/// CRLF terminators on some lines.
std::string csv_text(std::size_t rows) {
  std::string text = "t,gyro_x\n";
  char value[32];
  for (std::size_t i = 0; i < rows; ++i) {
    std::snprintf(value, sizeof value, "%+.8e", std::sin(0.001 * static_cast<double>(i)) * 3.0);
    text += row_line(static_cast<double>(i) * 0.01, value) + (i % 7 == 3 ? "\r\n" : "\n");
    if (i % 5000 == 4999) text += i % 10000 == 9999 ? "# comment\n" : "\n";
  }
  return text;
}

/// Line number (1-based) of data row `row` (0-based) in csv_text.
std::size_t line_of_row(std::size_t row) { return 2 + row + row / 5000; }

/// Byte offset where line `line` (1-based) starts.
std::size_t line_start(const std::string& text, std::size_t line) {
  std::size_t at = 0;
  for (std::size_t k = 1; k < line; ++k) at = text.find('\n', at) + 1;
  return at;
}

/// Replaces data row `row` with `line`.
void replace_row(std::string& text, std::size_t row, const std::string& line) {
  const std::size_t at = line_start(text, line_of_row(row));
  std::size_t end = text.find('\n', at);
  if (end > at && text[end - 1] == '\r') --end;
  text.replace(at, end - at, line);
}

/// The first data row of the second parallel chunk: the reader takes two rows serially, then
/// cuts 1 MB after them and moves on to the next line start.
std::size_t first_row_of_second_chunk(const std::string& text) {
  const std::size_t begin = line_start(text, line_of_row(2));
  const std::size_t cut = text.find('\n', begin + (std::size_t{1} << 20)) + 1;
  std::size_t row = 0;
  while (line_start(text, line_of_row(row)) < cut) row += 1000;
  row -= 1000;
  while (line_start(text, line_of_row(row)) < cut) ++row;
  return row;
}

TEST(ParallelCsv, EqualsTheSerialReaderWhateverTheThreadCount) {
  ThreadCountGuard guard;
  TempDir dir;
  const std::size_t rows = 200'000;  // about 5.5 MB: six chunks
  ReadOptions options;
  options.path = dir.write("record.csv", csv_text(rows));
  options.column = "gyro_x";
  const SerialRead serial = read_serially(options);
  ASSERT_EQ(serial.values.size(), rows);
  for (std::size_t threads : {1u, 2u, 8u}) {
    set_stats_thread_count(threads);
    const Record record = read_record(options);
    EXPECT_TRUE(record.values == serial.values) << threads << " threads";
    EXPECT_EQ(record.values.size(), rows);
    EXPECT_EQ(record.rate_hz, serial.rate_hz);
    EXPECT_EQ(record.start_time_s, serial.start_time_s);
  }
}

TEST(ParallelCsv, HeaderlessStable32TextEqualsSerial) {
  TempDir dir;
  std::string text = "# Stable32 style\n";
  for (int i = 0; i < 150'000; ++i) text += "  " + std::to_string(i % 977 * 1e-3) + "\n";
  ReadOptions options;
  options.path = dir.write("record.txt", text);
  options.rate_hz = 1.0;
  const Record record = read_record(options);
  EXPECT_TRUE(record.values == read_serially(options).values);
  EXPECT_EQ(record.values.size(), 150'000u);
}

TEST(ParallelCsv, ErrorsNameTheLineOfTheFirstBadRowInAnyChunk) {
  ThreadCountGuard guard;
  TempDir dir;
  const std::size_t rows = 160'000;
  const std::string good = csv_text(rows);
  const std::size_t boundary = first_row_of_second_chunk(good);
  ASSERT_GT(boundary, 30'000u);
  const auto t = [](std::size_t row) { return static_cast<double>(row) * 0.01; };
  struct Case {
    std::vector<std::size_t> rows;
    std::function<std::string(std::size_t)> line;  // the replacement of a row
  };
  const std::vector<Case> cases = {
      {{boundary - 1}, [&](std::size_t r) { return row_line(t(r), "abc"); }},
      {{boundary}, [&](std::size_t r) { return row_line(t(r), "nan"); }},
      {{boundary + 1}, [&](std::size_t r) { return row_line(t(r), "1,2"); }},
      {{120'001}, [&](std::size_t r) { return row_line(t(r), ""); }},
      {{150'000, 90'000}, [&](std::size_t r) { return row_line(t(r), "oops"); }},
      // Time: a jump (not uniformly sampled), a repeat (does not increase), at the first row of
      // a chunk (checked against the last row of the chunk before) and next to it.
      {{boundary}, [&](std::size_t r) { return row_line(t(r) + 0.02, "1"); }},
      {{boundary - 1}, [&](std::size_t r) { return row_line(t(r) + 0.02, "1"); }},
      {{boundary}, [&](std::size_t r) { return row_line(t(r - 1), "1"); }},
      {{boundary + 1}, [&](std::size_t r) { return row_line(t(r - 1), "1"); }},
  };
  for (const Case& bad : cases) {
    std::string text = good;
    for (std::size_t row : bad.rows) replace_row(text, row, bad.line(row));
    ReadOptions options;
    options.path = dir.write("bad.csv", text);
    options.column = "gyro_x";
    const std::string serial = error_of([&] { read_serially(options); });
    ASSERT_FALSE(serial.empty()) << bad.line(bad.rows.front());
    const std::size_t first_bad = *std::min_element(bad.rows.begin(), bad.rows.end());
    EXPECT_NE(serial.find("bad.csv:" + std::to_string(line_of_row(first_bad)) + ":"),
              std::string::npos)
        << serial;
    for (std::size_t threads : {1u, 2u, 8u}) {
      set_stats_thread_count(threads);
      EXPECT_EQ(error_of([&] { read_record(options); }), serial) << threads << " threads";
    }
  }
}

TEST(MappedFile, MapsReleasesAndReportsMissingFiles) {
  TempDir dir;
  const std::string path = dir.write("bytes.bin", std::string(10'000, 'x'));
  const MappedFile file(path);
  ASSERT_EQ(file.bytes().size(), 10'000u);
  file.release(0, 10'000);  // pages leave; reading maps them back
  EXPECT_EQ(static_cast<char>(file.bytes()[9'999]), 'x');
  EXPECT_EQ(MappedFile(dir.write("empty.bin", "")).bytes().size(), 0u);
  EXPECT_THROW(MappedFile(dir.file("missing.bin")), InputError);
}

std::string as_bytes(const std::vector<double>& values) {
  std::string bytes(values.size() * sizeof(double), '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

TEST(ReadPhaseRecord, MappedFloat64EqualsReadThenIntegrate) {
  ThreadCountGuard guard;
  TempDir dir;
  std::vector<double> rate(300'007);
  for (std::size_t i = 0; i < rate.size(); ++i) {
    rate[i] = 100.0 + std::sin(0.01 * static_cast<double>(i)) + 1e-3 * static_cast<double>(i % 13);
  }
  ReadOptions options;
  options.path = dir.write("rate.f64", as_bytes(rate));
  options.rate_hz = 100.0;
  std::vector<double> expected(rate.size() + 1);
  std::copy(rate.begin(), rate.end(), expected.begin() + 1);
  phase_from_rate_in_place(expected, 0.01);
  for (std::size_t threads : {1u, 2u, 8u}) {
    set_stats_thread_count(threads);
    const PhaseRecord mapped = read_phase_record(options);
    EXPECT_EQ(mapped.samples, rate.size());
    EXPECT_EQ(mapped.record.rate_hz, 100.0);
    EXPECT_EQ(mapped.record.column, "0");
    EXPECT_TRUE(mapped.record.values.empty());
    const std::vector<double> phase(mapped.phase().begin(), mapped.phase().end());
    EXPECT_TRUE(phase == expected) << threads << " threads";
  }
  // Phase data: the values as read.
  options.kind = DataKind::kPhase;
  const PhaseRecord as_phase = read_phase_record(options);
  EXPECT_TRUE(std::vector<double>(as_phase.phase().begin(), as_phase.phase().end()) == rate);
}

TEST(ReadPhaseRecord, MappedFloat64ErrorsAreThoseOfReadRecord) {
  TempDir dir;
  ReadOptions options;
  options.rate_hz = 1.0;
  std::vector<double> values(100'000, 1.0);
  values[70'000] = std::nan("");
  options.path = dir.write("nan.f64", as_bytes(values));
  const std::string expected = error_of([&] { read_record(options); });
  EXPECT_NE(expected.find("epoch 70000"), std::string::npos) << expected;
  EXPECT_EQ(error_of([&] { read_phase_record(options); }), expected);

  options.path = dir.write("one.f64", as_bytes({1.0}));
  EXPECT_EQ(error_of([&] { read_phase_record(options); }), error_of([&] { read_record(options); }));
  options.path = dir.write("odd.f64", std::string(12, '\0'));
  EXPECT_EQ(error_of([&] { read_phase_record(options); }), error_of([&] { read_record(options); }));
  options.path = dir.file("missing.f64");
  EXPECT_FALSE(error_of([&] { read_phase_record(options); }).empty());
  ReadOptions no_rate;
  no_rate.path = dir.write("norate.f64", as_bytes({1.0, 2.0, 3.0}));
  EXPECT_THROW(read_phase_record(no_rate), ConfigError);
}

}  // namespace
}  // namespace stochnav

#pragma once
// Streaming reader of one channel of a record file, block by block, with the same formats and
// checks as read_record (see record.hpp). Memory is one read buffer, independent of file length.

#include <cstddef>
#include <memory>
#include <vector>

#include "stochnav/io/record.hpp"

namespace stochnav {

class SampleReader final {
 public:
  /// Opens the file and reads its header. Throws InputError / ConfigError as read_record.
  explicit SampleReader(const ReadOptions& options);
  ~SampleReader();
  SampleReader(const SampleReader&) = delete;
  SampleReader& operator=(const SampleReader&) = delete;

  /// Appends up to max_samples samples to `out`; returns how many were appended (0 at the end).
  /// Throws InputError at the first malformed line or sample.
  std::size_t read_block(std::vector<double>& out, std::size_t max_samples);

  /// Appends every remaining sample to `out`, growing it once; returns how many. Plain
  /// (uncompressed) CSV and text files are memory-mapped and parsed in parallel chunks of about
  /// 1 MB (stats/parallel.hpp), each from a line start: the samples, the derived rate and the
  /// error (the first malformed line of the file, with its line number) are those read_block
  /// gives, whatever the thread count. Other files: read_block until the end.
  std::size_t read_all(std::vector<double>& out);

  /// Sampling rate in Hz: from the options, or from the time column once two samples are read.
  /// Valid after the first read_block that returned samples. The final, most accurate value
  /// (from the whole time span) is available after the end of the file.
  double rate_hz() const;
  double start_time_s() const;
  const std::string& column_name() const;
  /// Total samples returned so far.
  std::size_t samples_read() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stochnav

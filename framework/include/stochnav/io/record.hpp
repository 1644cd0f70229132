#pragma once
// A uniformly sampled record of one sensor channel, and how to read it from a file.
//
// Supported files (chosen by extension, then by content):
//   *.csv            CSV with a header row; the column is chosen by name or 0-based index; an
//                    optional column named `t` (or `t_s`, `time`) gives the sample times in s.
//   *.f64, *.f32     raw little-endian IEEE floats, `channels` interleaved channels per epoch.
//   anything else    text with one or more whitespace-separated numbers per line and `#`
//                    comment lines (Stable32 style); the first column unless one is chosen.
//   *.gz             any text format above, gzip-compressed.
// Every failure throws InputError naming file, line and a fix.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "stochnav/core/units.hpp"

namespace stochnav {

/// Sampling rates a record may have (Hz), from --rate or its time column; outside them the
/// statistics leave the range of a double (tau0 = 1e320 s, or a phase of rate x 1e-308 that
/// underflows), so a rate beyond them is refused (ConfigError for --rate, InputError for a time
/// column). 1e-9 Hz is one sample in 32 years; 1e9 Hz one a nanosecond.
inline constexpr double kMinRecordRateHz = 1e-9;
inline constexpr double kMaxRecordRateHz = 1e9;
/// A record whose largest sample magnitude is positive but below this is refused (InputError):
/// the squared differences of the Allan variance would underflow to 0 (values near 1e-170 gave
/// deviations of exactly 0). The mirror of the +/-1e100 bound on each sample.
inline constexpr double kMinRecordPeakMagnitude = 1e-100;

/// What the samples are: a rate (gyro rate, fractional frequency) or its integral (angle, clock
/// phase in s). Allan-variance estimators work on phase; rate records are integrated first.
enum class DataKind { kRate, kPhase };

/// One channel, uniformly sampled at rate_hz.
struct Record {
  std::vector<double> values;  ///< samples in `unit` (rate) or unit*s (phase)
  double rate_hz = 1.0;        ///< sampling rate (Hz); tau0 = 1 / rate_hz
  double start_time_s = 0.0;   ///< time of values[0] (s); 0 when the file has no time column
  DataKind kind = DataKind::kRate;
  Unit unit = Unit::kPlain;
  std::string source;  ///< file the record came from, for messages
  std::string column;  ///< column name (or index as text) within the file

  double tau0() const { return 1.0 / rate_hz; }
};

struct ReadOptions {
  std::string path;
  /// Column by name, or by 0-based index given as digits. Empty: the first column that is not
  /// a time column.
  std::string column;
  /// Sampling rate (Hz). Required unless the file has a time column, from which it is derived;
  /// when both are given they must agree to 1e-4 relative.
  std::optional<double> rate_hz;
  DataKind kind = DataKind::kRate;
  Unit unit = Unit::kPlain;
  /// Interleaved channels per epoch in raw binary files (.f64/.f32).
  int binary_channels = 1;
  /// When set, the bytes of the file consumed are added to it as reading goes (decompressed
  /// bytes for .gz): a progress display's counter (core/progress_bar.hpp, ProgressTicker).
  std::atomic<std::uint64_t>* bytes_read = nullptr;
};

/// Reads one channel of a file. Throws InputError on malformed content (non-numeric cell, NaN or
/// infinity, a sample beyond +/-1e100 (its squares would overflow the statistics), a record
/// whose largest magnitude is below kMinRecordPeakMagnitude (but not 0), a time column whose
/// rate is outside [kMinRecordRateHz, kMaxRecordRateHz], missing or
/// out-of-range column, ragged row, fewer than 2 samples, non-uniform or decreasing time, CR-only
/// line endings; a UTF-8 byte-order mark is skipped)
/// and ConfigError on inconsistent options (no rate and no time column, a rate outside
/// [kMinRecordRateHz, kMaxRecordRateHz]).
Record read_record(const ReadOptions& options);

/// read_record with `leading_zeros` zeros before the samples in values (values.size() ==
/// leading_zeros + samples), allocated with them: room for an in-place transform of the record
/// (stats/phase.hpp) without a second array. The checks (two samples at least) count samples.
Record read_record(const ReadOptions& options, std::size_t leading_zeros);

class SampleReader;

/// A Record holding no samples yet: rate, start time, kind, unit, source and column of the
/// channel `reader` reads with `options` (for estimators that stream the samples themselves).
Record describe_record(const ReadOptions& options, const SampleReader& reader);

/// Column names of a CSV file's header (or "0", "1", ... for headerless text), for messages.
std::vector<std::string> list_columns(const std::string& path);

}  // namespace stochnav

#pragma once
// Access to the Stable32 reference tables and their input records under
// STOCHNAV_SHARED_DATA_DIR/allan (see SOURCES.md there for the table layout).

#include <gtest/gtest.h>

#include <cctype>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "stable32_table.hpp"

namespace stochnav::stats_test {

/// STOCHNAV_SHARED_DATA_DIR/allan.
std::filesystem::path allan_data_dir();

/// Skips the current test, naming the missing folder, when the shared data are absent.
#define STOCHNAV_SKIP_WITHOUT_ALLAN_DATA()                                           \
  do {                                                                               \
    const auto allan_dir = ::stochnav::stats_test::allan_data_dir();                 \
    if (!std::filesystem::is_directory(allan_dir)) {                                 \
      GTEST_SKIP() << "shared reference data folder missing: " << allan_dir.string() \
                   << " (set STOCHNAV_SHARED_DATA_DIR when configuring)";            \
    }                                                                                \
  } while (false)

using Stable32Row = ::stochnav::testing::Stable32Row;

/// Rows of a table file relative to allan_data_dir(); throws std::runtime_error when unreadable.
std::vector<Stable32Row> read_stable32_table(const std::string& relative_path);

/// The table's averaging factors (its AF column), in its order.
std::vector<std::size_t> averaging_factors_of(const std::vector<Stable32Row>& rows);

/// Expects our averaging factors to be the table's, or with `table_is_prefix` to start with
/// them (runs Stable32 ended early, rows allantools commented out).
void expect_table_factors(const std::vector<std::size_t>& ours,
                          const std::vector<std::size_t>& table_m, bool table_is_prefix);

/// Tau as Stable32's Tau column prints it ("%.4e").
std::string tau_as_stable32_prints_it(double tau_s);

/// The GoogleTest name of a table case (any struct with a `table` path): the path with every
/// character but letters and digits turned into '_'.
template <typename Case>
std::string table_case_name(const ::testing::TestParamInfo<Case>& info) {
  std::string name = info.param.table;
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

/// The input records of the tables, as phase (converted as SOURCES.md prescribes).
enum class ReferenceRecord {
  kPhaseDat,           ///< phasedat/PHASE.DAT, phase, tau0 = 1 s
  kKeysightTic,        ///< keysight53230a_tic/tic_phase.txt, phase, tau0 = 1 s
  kOcxo,               ///< ocxo_freq/ocxo_frequency.txt, Hz -> y = (f - 1e7) / 1e7, tau0 = 1 s
  kPinkFrequency,      ///< pink_frequency/pink_frequency.txt, fractional frequency, tau0 = 42 s
  kPinkFrequencyTau1,  ///< the same record with tau0 = 1 s (s32_oadev_octave.txt)
  kGps,                ///< gps_1pps/gps_1pps_phase_data.txt.gz, phase, tau0 = 1 s
  kCs5071a,            ///< cs5071a/5071A_phase.txt.gz, phase, tau0 = 1 s
  kNbs14Frequency,     ///< nbs14/nbs14_1000_freq.txt, fractional frequency, tau0 = 1 s
};

struct ReferencePhase {
  std::vector<double> phase;  ///< phase points (s)
  double tau0_s = 1.0;
};

/// Loaded through stochnav::read_record once per process and cached.
const ReferencePhase& reference_phase(ReferenceRecord record);

}  // namespace stochnav::stats_test

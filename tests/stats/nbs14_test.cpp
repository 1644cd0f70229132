// The NBS14 test suite (NIST SP 1065 pp. 107-108; W. Riley, "The Calculation of Time Domain
// Frequency Stability"): the 1000-point and 10-point data sets with their published deviations.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "stable32_reference.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav {
namespace {

/// name -> cells after the name, from the reference CSV ('#' lines skipped).
std::map<std::string, std::vector<std::string>> read_reference_csv(const std::string& file) {
  std::ifstream in(stats_test::allan_data_dir() / "nbs14" / file);
  std::map<std::string, std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line.front() == '#') continue;
    std::istringstream cells(line);
    std::string name;
    std::getline(cells, name, ',');
    std::string cell;
    while (std::getline(cells, cell, ',')) rows[name].push_back(cell);
  }
  return rows;
}

std::vector<double> read_values(const std::string& file, DataKind kind) {
  ReadOptions options;
  options.path = (stats_test::allan_data_dir() / "nbs14" / file).string();
  options.rate_hz = 1.0;
  options.kind = kind;
  return read_record(options).values;
}

const std::map<std::string, Deviation> kNames = {
    {"ADEV", Deviation::kAdev},    {"OADEV", Deviation::kOadev}, {"MDEV", Deviation::kMdev},
    {"TDEV", Deviation::kTdev},    {"HDEV", Deviation::kHdev},   {"OHDEV", Deviation::kOhdev},
    {"TOTDEV", Deviation::kTotdev}};

TEST(Nbs14, ThousandPointDeviationsAtTau1_10_100) {
  STOCHNAV_SKIP_WITHOUT_ALLAN_DATA();
  const auto reference = read_reference_csv("nbs14_1000_reference.csv");
  const auto& data = stats_test::reference_phase(stats_test::ReferenceRecord::kNbs14Frequency);
  ASSERT_EQ(data.phase.size(), 1001u);
  for (const auto& [name, kind] : kNames) {
    const auto& cells = reference.at(name);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto m = static_cast<std::size_t>(std::stoul(cells[k]));
      const double expected = std::stod(cells[3 + k]);
      EXPECT_NEAR(deviation_value(kind, data.phase, 1.0, m) / expected, 1.0, 1e-4)
          << name << " tau " << m;
    }
  }
}

TEST(Nbs14, IntegratedThousandPointsArePhaseDat) {
  // SOURCES.md: PHASE.DAT is the NBS14 frequency set, mean removed and integrated.
  STOCHNAV_SKIP_WITHOUT_ALLAN_DATA();
  const auto& ours = stats_test::reference_phase(stats_test::ReferenceRecord::kNbs14Frequency);
  const auto& stable32 = stats_test::reference_phase(stats_test::ReferenceRecord::kPhaseDat);
  ASSERT_EQ(ours.phase.size(), stable32.phase.size());
  for (std::size_t i = 0; i < ours.phase.size(); ++i) {
    ASSERT_NEAR(ours.phase[i], stable32.phase[i], 1e-12) << "point " << i;
  }
}

TEST(Nbs14, TenPointDeviationsFromPhaseAndFrequency) {
  STOCHNAV_SKIP_WITHOUT_ALLAN_DATA();
  const auto reference = read_reference_csv("nbs14_10_reference.csv");
  const std::vector<double> phase = read_values("nbs14_10_phase.txt", DataKind::kPhase);
  const std::vector<double> from_frequency =
      phase_from_rate(read_values("nbs14_10_freq.txt", DataKind::kRate), 1.0);
  ASSERT_EQ(phase.size(), 10u);
  ASSERT_EQ(from_frequency.size(), 10u);
  for (const auto& [name, kind] : kNames) {
    const auto& cells = reference.at(name);
    for (std::size_t m = 1; m <= 2; ++m) {
      const double expected = std::stod(cells[m - 1]);
      EXPECT_NEAR(deviation_value(kind, phase, 1.0, m) / expected, 1.0, 1e-4) << name << m;
      EXPECT_NEAR(deviation_value(kind, from_frequency, 1.0, m) / expected, 1.0, 1e-4) << name << m;
    }
  }
}

}  // namespace
}  // namespace stochnav

#include "stable32_reference.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <mutex>
#include <stdexcept>

#include "stochnav/io/record.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav::stats_test {

std::filesystem::path allan_data_dir() {
  return std::filesystem::path(STOCHNAV_SHARED_DATA_DIR) / "allan";
}

std::vector<Stable32Row> read_stable32_table(const std::string& relative_path) {
  return testing::read_stable32_table_file(allan_data_dir() / relative_path);
}

std::vector<std::size_t> averaging_factors_of(const std::vector<Stable32Row>& rows) {
  std::vector<std::size_t> factors;
  factors.reserve(rows.size());
  for (const auto& row : rows) factors.push_back(row.m);
  return factors;
}

void expect_table_factors(const std::vector<std::size_t>& ours,
                          const std::vector<std::size_t>& table_m, bool table_is_prefix) {
  if (table_is_prefix && ours.size() >= table_m.size()) {
    EXPECT_TRUE(std::equal(table_m.begin(), table_m.end(), ours.begin()))
        << "the table's factors are not the start of ours";
  } else {
    EXPECT_EQ(ours, table_m);
  }
}

std::string tau_as_stable32_prints_it(double tau_s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4e", tau_s);
  return text;
}

namespace {

ReferencePhase load_phase(const std::string& relative_path, double tau0_s) {
  ReadOptions options;
  options.path = (allan_data_dir() / relative_path).string();
  options.rate_hz = 1.0 / tau0_s;
  options.kind = DataKind::kPhase;
  return {read_record(options).values, tau0_s};
}

ReferencePhase load_rate(const std::string& relative_path, double tau0_s,
                         double (*to_rate)(double)) {
  ReadOptions options;
  options.path = (allan_data_dir() / relative_path).string();
  options.rate_hz = 1.0 / tau0_s;
  options.kind = DataKind::kRate;
  std::vector<double> rate = read_record(options).values;
  if (to_rate != nullptr) {
    for (double& value : rate) value = to_rate(value);
  }
  return {phase_from_rate(rate, tau0_s), tau0_s};
}

ReferencePhase load(ReferenceRecord record) {
  switch (record) {
    case ReferenceRecord::kPhaseDat:
      return load_phase("phasedat/PHASE.DAT", 1.0);
    case ReferenceRecord::kKeysightTic:
      return load_phase("keysight53230a_tic/tic_phase.txt", 1.0);
    case ReferenceRecord::kOcxo:
      return load_rate("ocxo_freq/ocxo_frequency.txt", 1.0,
                       [](double hz) { return (hz - 1.0e7) / 1.0e7; });
    case ReferenceRecord::kPinkFrequency:
      return load_rate("pink_frequency/pink_frequency.txt", 42.0, nullptr);
    case ReferenceRecord::kPinkFrequencyTau1:
      return load_rate("pink_frequency/pink_frequency.txt", 1.0, nullptr);
    case ReferenceRecord::kGps:
      return load_phase("gps_1pps/gps_1pps_phase_data.txt.gz", 1.0);
    case ReferenceRecord::kCs5071a:
      return load_phase("cs5071a/5071A_phase.txt.gz", 1.0);
    case ReferenceRecord::kNbs14Frequency:
      return load_rate("nbs14/nbs14_1000_freq.txt", 1.0, nullptr);
  }
  throw std::logic_error("unknown reference record");
}

}  // namespace

const ReferencePhase& reference_phase(ReferenceRecord record) {
  static std::mutex mutex;
  static std::map<ReferenceRecord, ReferencePhase> cache;
  const std::lock_guard lock(mutex);
  auto found = cache.find(record);
  if (found == cache.end()) found = cache.emplace(record, load(record)).first;
  return found->second;
}

}  // namespace stochnav::stats_test

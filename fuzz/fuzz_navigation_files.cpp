// The streaming readers of a navigation run's inputs: imu.csv (increments or rates, uniform
// time steps), truth.csv, the generic CSV table under them, and the PSINS IMU text format.

#include <limits>

#include "fuzz_support.hpp"
#include "stochnav/experiment/navigation_files.hpp"
#include "stochnav/io/csv_table_reader.hpp"
#include "stochnav/io/psins_imu.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stochnav;
  const fuzz::ScratchFile file(data, size, "input.csv");
  fuzz::expect_typed_errors([&] {
    ImuFileReader imu(file.path());
    ImuIncrement increment;
    while (imu.next(increment)) {
      if (!(increment.dt_s > 0.0)) std::abort();  // the reader's contract
    }
  });
  fuzz::expect_typed_errors([&] {
    TruthFileReader truth(file.path());
    NavState state;
    double previous_t_s = -std::numeric_limits<double>::infinity();
    while (truth.next(state)) {
      if (!(state.t_s > previous_t_s)) std::abort();  // the reader's contract: time increases
      previous_t_s = state.t_s;
    }
  });
  fuzz::expect_typed_errors([&] {
    constexpr std::string_view kColumns[] = {"t", "x"};
    CsvTableReader table(file.path(), kColumns);
    double values[2];
    while (table.next(values)) {
    }
  });
  fuzz::expect_typed_errors([&] { read_psins_imu(file.path()); });
  return 0;
}

// read_record on CSV text (sample_reader: header, columns, time axis, parallel chunks) with the
// column and rate options a user can give, chosen by the first byte.

#include "fuzz_support.hpp"
#include "stochnav/io/record.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stochnav;
  const std::uint8_t selector = size > 0 ? data[0] : 0;
  const fuzz::ScratchFile file(data, size, "input.csv");
  ReadOptions options;
  options.path = file.path();
  if (selector & 1) options.rate_hz = 100.0;
  if (selector & 2) options.column = std::string(1, (selector & 4) ? '1' : 'x');
  if (selector & 8) options.kind = DataKind::kPhase;
  fuzz::expect_typed_errors([&] {
    const Record record = read_record(options);
    if (record.values.size() < 2 || !(record.rate_hz > 0.0)) std::abort();  // documented contract
  });
  fuzz::expect_typed_errors([&] { list_columns(file.path()); });
  return 0;
}

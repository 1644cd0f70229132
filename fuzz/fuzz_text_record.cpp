// read_record on plain text (Stable32 style: '#' comments, whitespace-separated columns), plain
// and gzip-compressed (the .gz path takes the input as compressed bytes).

#include "fuzz_support.hpp"
#include "stochnav/io/record.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stochnav;
  const bool gzip = size > 1 && data[0] == 0x1f && data[1] == 0x8b;
  const fuzz::ScratchFile file(data, size, gzip ? "input.txt.gz" : "input.txt");
  ReadOptions options;
  options.path = file.path();
  options.rate_hz = 1.0;
  if (size % 3 == 0) options.column = std::string(1, '1');  // not = "1": GCC 12 -Wrestrict false positive
  fuzz::expect_typed_errors([&] {
    const Record record = read_record(options, 3);
    if (record.values.size() < 5) std::abort();  // 3 leading zeros + at least 2 samples
  });
  return 0;
}

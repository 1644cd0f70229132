// read_record on raw little-endian floats (.f64, .f32) with 1 to 4 interleaved channels: sizes
// that are not whole epochs, NaN, infinity and huge values.

#include "fuzz_support.hpp"
#include "stochnav/io/record.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stochnav;
  if (size == 0) return 0;
  const std::uint8_t selector = data[0];
  const bool narrow = (selector & 1) != 0;
  const fuzz::ScratchFile file(data + 1, size - 1, narrow ? "input.f32" : "input.f64");
  ReadOptions options;
  options.path = file.path();
  options.rate_hz = 10.0;
  options.binary_channels = 1 + ((selector >> 1) & 3);
  if (selector & 8) options.column = std::to_string((selector >> 4) & 3);
  fuzz::expect_typed_errors([&] { read_record(options); });
  return 0;
}

// The noise-model JSON: parsing and validation (noise_model_from_json), then the written form
// must read back to the same model (to_json round trip).

#include "fuzz_support.hpp"
#include "stochnav/model/noise_model_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stochnav;
  const auto document = fuzz::parse_json(data, size);
  if (!document) return 0;
  fuzz::expect_typed_errors([&] {
    const NoiseModel model = noise_model_from_json(*document);
    fuzz::must_not_throw([&] {
      const NoiseModel again = noise_model_from_json(to_json(model));
      if (again.terms.size() != model.terms.size()) std::abort();
    });
  });
  return 0;
}

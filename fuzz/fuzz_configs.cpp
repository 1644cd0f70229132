// The run, experiment and scenario configs: the same document through each parser (the first
// byte of the input chooses which, the rest is the JSON), as `stochnav run`, `compare` and
// `simulate scenario` read them, with the files a config names resolved in a scratch folder.

#include "fuzz_support.hpp"
#include "stochnav/experiment/experiment_config.hpp"
#include "stochnav/plugin/run_config.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stochnav;
  if (size == 0) return 0;
  const auto document = fuzz::parse_json(data + 1, size - 1);
  if (!document) return 0;
  const fuzz::ScratchFile file(data + 1, size - 1, "config.json");
  switch (data[0] % 3) {
    case 0:
      fuzz::expect_typed_errors([&] { plugin::parse_run_config(*document, file.folder(), {}); });
      break;
    case 1:
      fuzz::expect_typed_errors([&] { experiment_config_from_json(*document, file.path()); });
      break;
    default:
      fuzz::expect_typed_errors([&] {
        const ScenarioConfig config = scenario_config_from_json(*document, file.path());
        fuzz::must_not_throw([&] { scenario_config_from_json(to_json(config), "round trip"); });
      });
  }
  return 0;
}

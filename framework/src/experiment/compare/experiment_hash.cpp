#include "stochnav/experiment/experiment_hash.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>

namespace stochnav {
namespace {

std::uint64_t fnv1a_64(const std::string& text) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV offset basis
  for (const unsigned char byte : text) {
    hash ^= byte;
    hash *= 0x100000001b3ULL;  // FNV prime
  }
  return hash;
}

nlohmann::json scenario_content(const ExperimentConfig& config) {
  if (!config.scenario_config) return nullptr;
  std::ifstream in(*config.scenario_config);
  const nlohmann::json content = nlohmann::json::parse(in, nullptr, false);
  return content.is_discarded() ? nlohmann::json(config.scenario_config->string()) : content;
}

}  // namespace

std::string experiment_hash(const ExperimentConfig& config) {
  nlohmann::json document = config.document;
  if (document.is_object()) document.erase("threads");
  const nlohmann::json fingerprint = {{"document", document},
                                      {"seeds", config.seeds},
                                      {"scenario_overrides", config.scenario_overrides},
                                      {"scenario", scenario_content(config)}};
  return fmt::format("{:016x}", fnv1a_64(fingerprint.dump()));
}

}  // namespace stochnav

#pragma once
// Reading a JSON file a test or the CLI under test wrote.

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace stochnav::testing {

/// The parsed contents of `path`; throws nlohmann::json::parse_error if it is not JSON.
inline nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace stochnav::testing

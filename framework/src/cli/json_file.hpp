#pragma once
// Reading JSON documents given on the command line.

#include <nlohmann/json.hpp>

#include <string>

namespace stochnav::cli {

/// Parses the JSON file at `path`. Throws InputError naming the file (and the parser's line and
/// column) when it cannot be read or parsed; `option` names the option that gave the path.
nlohmann::json read_json_file(const std::string& path, const std::string& option);

}  // namespace stochnav::cli

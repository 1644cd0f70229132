#include "json_file.hpp"

#include <fstream>

#include "stochnav/core/errors.hpp"

namespace stochnav::cli {

nlohmann::json read_json_file(const std::string& path, const std::string& option) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file; check the path given with " + option);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(path + ": not valid JSON (" + std::string(error.what()) +
                     "); fix the syntax at that position");
  }
}

}  // namespace stochnav::cli

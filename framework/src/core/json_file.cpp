#include "stochnav/core/json_file.hpp"

#include <fstream>
#include <string>

#include "stochnav/core/errors.hpp"

namespace stochnav {

nlohmann::json read_json_file(const std::filesystem::path& file, std::string_view what) {
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) {
    throw InputError(file.string() + ": is a folder; expected a " + std::string(what) +
                     " file (JSON)");
  }
  std::ifstream in(file);
  if (!in) {
    throw InputError(file.string() + ": cannot open the " + std::string(what) + "; check the path");
  }
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& parse_error) {
    throw InputError(file.string() + ": not valid JSON (" + std::string(parse_error.what()) +
                     "); fix the syntax");
  }
}

}  // namespace stochnav

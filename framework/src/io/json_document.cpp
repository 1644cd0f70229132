#include "stochnav/io/json_document.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "stochnav/core/errors.hpp"

namespace stochnav {

nlohmann::json read_json_document(const std::filesystem::path& path, std::string_view what) {
  const std::string name = path.string();
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(name + ": is a folder, not a JSON file; give " + std::string(what) +
                     " as a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(name + ": cannot open (" + std::strerror(errno) + "); check the path of " +
                     std::string(what));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    throw InputError(name + ": read error (" + std::strerror(errno) + "); check the file");
  }
  try {
    return nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& problem) {
    throw InputError(name + ": not valid JSON (" + problem.what() +
                     "); fix the syntax at that position");
  } catch (const nlohmann::json::out_of_range& problem) {
    // 406: a number the parser cannot hold in a double.
    throw InputError(name + ": a number is out of range (" + problem.what() +
                     "); numbers must lie within +/-1.7e308");
  } catch (const nlohmann::json::exception& problem) {
    throw InputError(name + ": not valid JSON (" + problem.what() + "); fix the file");
  }
}

}  // namespace stochnav

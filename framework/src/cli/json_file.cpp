#include "json_file.hpp"

#include "stochnav/io/json_document.hpp"

namespace stochnav::cli {

nlohmann::json read_json_file(const std::string& path, const std::string& option) {
  return read_json_document(path, option);
}

}  // namespace stochnav::cli

#include "stochnav/io/sample_count_bound.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

bool ends_with(std::string_view text, std::string_view tail) {
  return text.size() >= tail.size() && text.substr(text.size() - tail.size()) == tail;
}

}  // namespace

std::optional<std::size_t> sample_count_bound(const ReadOptions& options) {
  const std::string& path = options.path;
  if (ends_with(path, ".gz")) return std::nullopt;
  std::error_code error;
  const auto bytes = std::filesystem::file_size(path, error);
  if (error)
    throw InputError(path + ": cannot read the file (" + error.message() + "); check the path");
  const std::size_t channels = static_cast<std::size_t>(std::max(options.binary_channels, 1));
  if (ends_with(path, ".f64")) return bytes / (sizeof(double) * channels);
  if (ends_with(path, ".f32")) return bytes / (sizeof(float) * channels);
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) throw InputError(path + ": cannot open the file; check the path and its permissions");
  std::vector<char> buffer(std::size_t{1} << 20);
  std::size_t lines = 1;  // a last line without a newline
  for (std::size_t got; (got = std::fread(buffer.data(), 1, buffer.size(), file.get())) > 0;) {
    lines += static_cast<std::size_t>(std::count(buffer.data(), buffer.data() + got, '\n'));
  }
  return lines;
}

}  // namespace stochnav

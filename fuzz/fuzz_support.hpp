#pragma once
// Shared by the fuzz targets: the library's readers take file paths, so an input is written to
// a scratch file first; the library's typed errors (InputError, ConfigError) are the expected
// answer to a malformed input and are swallowed; anything else escapes
// LLVMFuzzerTestOneInput and ends the process (a finding).

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/json_document.hpp"

namespace stochnav::fuzz {

/// A file in a scratch folder of this process that holds the current input.
class ScratchFile final {
 public:
  ScratchFile(const std::uint8_t* data, std::size_t size, std::string_view name) {
    folder_ = std::filesystem::temp_directory_path() /
              ("stochnav_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder_);
    path_ = folder_ / std::string(name);
    std::ofstream(path_, std::ios::binary)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  ~ScratchFile() {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  std::string path() const { return path_.string(); }
  const std::filesystem::path& folder() const { return folder_; }

 private:
  std::filesystem::path folder_;
  std::filesystem::path path_;
};

/// Runs `body`; the library's typed errors are the expected outcome of a malformed input.
template <typename Body>
void expect_typed_errors(Body&& body) {
  try {
    body();
  } catch (const InputError&) {
  } catch (const ConfigError&) {
  }
}

/// Runs `body`, which must not throw at all (a round trip of something the library accepted).
template <typename Body>
void must_not_throw(Body&& body) {
  try {
    body();
  } catch (...) {
    std::abort();
  }
}

/// The input as a JSON document, or nothing when it is not JSON (the parse itself is the
/// parser's business; the targets fuzz what the library does with documents).
/// The input through the one JSON reader the tool uses (io/json_document.hpp: syntax, range,
/// duplicate keys); nothing when it refuses the input (InputError), as the tool would.
inline std::optional<nlohmann::json> parse_json(const std::uint8_t* data, std::size_t size) {
  try {
    return parse_json_document(std::string(reinterpret_cast<const char*>(data), size), "input");
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace stochnav::fuzz

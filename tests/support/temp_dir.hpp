#pragma once
// A fresh temporary folder per test, removed afterwards, and small file helpers.

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>

namespace stochnav::testing {

class TempDir {
 public:
  TempDir() {
    std::random_device entropy;
    path_ = std::filesystem::temp_directory_path() /
            ("stochnav_test_" + std::to_string(entropy()) + std::to_string(entropy()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(std::string_view name) const { return (path_ / name).string(); }

  /// Writes `content` to a file in the folder and returns its path.
  std::string write(std::string_view name, std::string_view content) const {
    const std::string full = file(name);
    std::ofstream(full, std::ios::binary).write(content.data(),
                                                static_cast<std::streamsize>(content.size()));
    return full;
  }

 private:
  std::filesystem::path path_;
};

/// The shared data folder (../shared/data), or an empty string when it is absent.
inline std::string shared_data_path(std::string_view relative) {
  const std::filesystem::path full = std::filesystem::path(STOCHNAV_SHARED_DATA_DIR) / relative;
  return std::filesystem::exists(full) ? full.string() : std::string();
}

}  // namespace stochnav::testing

/// Skips the current test when a shared data file is missing, naming it.
#define STOCHNAV_REQUIRE_SHARED_DATA(var, relative)                                        \
  const std::string var = ::stochnav::testing::shared_data_path(relative);                \
  if (var.empty()) {                                                                       \
    GTEST_SKIP() << "shared test data missing: " << STOCHNAV_SHARED_DATA_DIR << "/"        \
                 << (relative) << " (tests read it from ../shared/data beside the repo)"; \
  }

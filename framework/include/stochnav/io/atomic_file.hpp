#pragma once
// Output files that appear whole or not at all.

#include <filesystem>
#include <string>
#include <string_view>

namespace stochnav {

/// Writes `content` to a temporary file beside `path` and renames it into place. Throws
/// InputError naming the path if the folder cannot be written.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// A temporary path in the same folder as `path` (so a rename is atomic), removed on
/// destruction unless commit() moved it to `path`.
class PendingFile final {
 public:
  explicit PendingFile(std::filesystem::path path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::filesystem::path& temporary_path() const { return temporary_; }
  /// Renames the temporary file to the final path. Throws InputError on failure.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

}  // namespace stochnav

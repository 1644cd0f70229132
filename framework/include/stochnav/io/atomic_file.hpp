#pragma once
// Output files that appear whole or not at all.

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "stochnav/core/temporary_files.hpp"

namespace stochnav {

/// Writes `content` to a temporary file beside `path` and renames it into place. Throws
/// InputError naming the path and the system's reason (no space left, permission denied, no
/// such folder) if it cannot be written.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// Throws InputError "PATH: cannot write (REASON); ..." with REASON from `errno_value` (0: an
/// unknown reason). For writers whose stream failed: pass errno right after the failure.
[[noreturn]] void throw_write_error(const std::filesystem::path& path, int errno_value);

/// A temporary path in the same folder as `path` (so a rename is atomic), removed on
/// destruction unless commit() moved it to `path`, and on SIGINT/SIGTERM once the CLI installed
/// the signal cleanup (core/temporary_files.hpp).
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
  TemporaryPath registration_;
  bool committed_ = false;
};

/// An output folder a failure does not leave behind. The constructor creates it (and missing
/// parents); if it did not exist, the destructor removes it again, whole, unless keep() was
/// called, and so does a fatal signal meanwhile. A folder that existed is left alone. Throws
/// InputError naming the folder and the system's reason if it cannot be created.
class OutputFolder final {
 public:
  explicit OutputFolder(std::filesystem::path path);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// The folder stays (the outputs in it are complete).
  void keep();

 private:
  std::filesystem::path path_;
  std::filesystem::path created_;  // the outermost folder this object created; empty if none
  std::unique_ptr<TemporaryPath> registration_;
};

}  // namespace stochnav

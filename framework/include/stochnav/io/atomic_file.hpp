#pragma once
// Output files that appear whole or not at all. Where an output path goes (a regular file
// replaced atomically, a link followed, a FIFO or device written in place, a folder, socket or
// block device refused) is io/output_target.hpp's rule; docs/reliability.md states it for users.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "stochnav/core/temporary_files.hpp"
#include "stochnav/io/folder_lock.hpp"

namespace stochnav {

/// Writes `content` to a temporary file beside `path` and renames it into place (a FIFO or a
/// character device: written in place; a link: its target replaced; output_target.hpp). Throws
/// InputError naming the path and the system's reason (no space left, permission denied, no
/// such folder) if it cannot be written, or if `path` is a folder, a socket or a block device.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// Throws InputError "PATH: cannot write (REASON); ..." with REASON from `errno_value` (0: an
/// unknown reason). For writers whose stream failed: pass errno right after the failure.
[[noreturn]] void throw_write_error(const std::filesystem::path& path, int errno_value);

/// A temporary file in the same folder as `path` (so a rename is atomic), removed on
/// destruction unless commit() moved it to `path`, and on SIGINT/SIGTERM once the CLI installed
/// the signal cleanup (core/temporary_files.hpp). The constructor creates it, empty, under the
/// cleanup's lock; write it through open_stream() or open_file(), which do not create it again
/// once the cleanup has removed it. Throws InputError "PATH: cannot write (REASON); ..." when
/// the temporary file cannot be created.
///
/// `path` is resolved first (resolve_output_target): final_path() is a link's final target, and
/// a regular file replaced keeps its permission bits (commit() gives them to the new file). A FIFO or a character device is written in
/// place: temporary_path() is final_path() itself, opened for writing (waiting for a FIFO's
/// reader), commit() renames nothing and destruction removes nothing.
///
/// The first PendingFile of a process in a folder removes the temporary files there of
/// processes that died (io/stale_temporaries.hpp); the temporary file is locked (flock) while
/// this object lives, the mark of a live writer.
class PendingFile final {
 public:
  explicit PendingFile(std::filesystem::path path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::filesystem::path& final_path() const { return final_; }
  const std::filesystem::path& temporary_path() const { return temporary_; }
  /// True when the output is written in place (a FIFO or a character device).
  bool in_place() const { return in_place_; }
  /// The temporary file opened for writing (binary, at its start). Throws InputError if it
  /// cannot be opened.
  std::ofstream open_stream() const;
  /// The same as a C stream ("r+b"); the caller closes it. Throws InputError.
  std::FILE* open_file() const;
  /// Renames the temporary file to the final path (in place: nothing to do). Throws InputError
  /// on failure.
  void commit();

 private:
  std::filesystem::path final_;
  bool in_place_ = false;
  std::filesystem::path temporary_;
  std::optional<TemporaryPath> registration_;  // empty in place: a device is never removed
  int lock_fd_ = -1;                            // holds the temporary file's lock
  bool committed_ = false;
};

/// Writes `content` into the temporary file of `pending` (commit() is the caller's). Throws
/// InputError as write_file_atomically.
void write_pending_file(const PendingFile& pending, std::string_view content);

/// An output folder a failure does not leave behind, with one writer. The constructor creates
/// it (and missing parents) and locks it (io/folder_lock.hpp: a second process writing into it
/// is refused with InputError); if it did not exist, the destructor removes it again, whole,
/// unless keep() was called, and so does a fatal signal meanwhile. A folder that existed is
/// left alone. Throws InputError naming the folder and the system's reason if it cannot be
/// created.
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
  std::optional<FolderLock> lock_;
};

}  // namespace stochnav

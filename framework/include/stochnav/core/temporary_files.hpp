#pragma once
// Files and folders that must not outlive an interrupted process: a half-written output's
// temporary file, a scratch folder. Paths are registered for their lifetime; when the process
// receives SIGINT, SIGTERM or SIGHUP after install_signal_cleanup(), every registered path is
// removed (a folder with its contents) and the signal is raised again with its default action,
// so the exit status still says which signal ended the process.

#include <cstdint>
#include <filesystem>
#include <system_error>

namespace stochnav {

/// Registers `path` for removal on a fatal signal while the object lives. Thread-safe. The
/// object does not remove the path itself on destruction: its owner does that (PendingFile,
/// OutputFolder); release() ends the registration early (after a commit).
class TemporaryPath final {
 public:
  /// kWhole: the path with everything in it. kIfEmpty: a folder only when it is empty (one
  /// other processes may share), removed after every kWhole path, the latest registered first.
  enum class Removal { kWhole, kIfEmpty };

  explicit TemporaryPath(std::filesystem::path path, Removal removal = Removal::kWhole);
  ~TemporaryPath();
  TemporaryPath(const TemporaryPath&) = delete;
  TemporaryPath& operator=(const TemporaryPath&) = delete;

  void release();

 private:
  std::uint64_t id_ = 0;  // 0: not registered
};

/// Installs the cleanup for SIGINT, SIGTERM and SIGHUP: a handler that only hands the signal
/// through a pipe to a thread, which removes the registered paths and re-raises the signal with
/// its default action. Child processes (gnuplot) get the default actions back at exec. Call it
/// once, early in main(). Idempotent. A signal the process was started with ignored stays
/// ignored.
void install_signal_cleanup();

/// std::filesystem::create_directories, excluded from the signal cleanup: it runs before the
/// cleanup or not at all (once the cleanup has begun it waits for the process to end). Every
/// folder an output or scratch path needs is made with it, so that a worker thread cannot make
/// again a folder the cleanup has just removed (it did: compare's OUT/.scenarios/seed_N, and
/// with it OUT, outlived a SIGTERM).
void create_directories_before_cleanup(const std::filesystem::path& path, std::error_code& error);

/// Removes every registered path now (what the signal thread does). For tests.
void remove_registered_paths();

}  // namespace stochnav

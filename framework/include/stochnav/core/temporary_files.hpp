#pragma once
// Files and folders that must not outlive an interrupted process: a half-written output's
// temporary file, a scratch folder. Paths are registered for their lifetime; when the process
// receives SIGINT, SIGTERM or SIGHUP after install_signal_cleanup(), every registered path is
// removed (a folder with its contents) and the signal is raised again with its default action,
// so the exit status still says which signal ended the process. Folders, temporary files and
// child processes are made under the cleanup's lock, so none appears after the cleanup.

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <system_error>
#include <vector>

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

/// Runs `action` under the cleanup's lock: before the cleanup or not at all (once the cleanup
/// has begun the calling thread waits for the process to end). For a short file-system action
/// that must not follow the cleanup: opening a registered temporary file.
void run_before_cleanup(const std::function<void()>& action);

/// Creates the empty file `path` (or empties it) with run_before_cleanup. PendingFile makes its
/// temporary file with it, so a worker cannot make again a file the cleanup has removed.
void create_file_before_cleanup(const std::filesystem::path& path, std::error_code& error);

/// A child process the signal cleanup kills (SIGKILL) and waits for before it removes the
/// registered paths, so the child cannot write into them afterwards (gnuplot drawing into a
/// temporary picture after the tool was killed).
class CleanupChild final {
 public:
  /// Starts `argv` (argv[0] looked up on PATH) under the cleanup's lock, with its standard
  /// output and error on one pipe (output_fd()). Throws InputError naming the program and the
  /// system's reason when it cannot start.
  explicit CleanupChild(const std::vector<std::string>& argv);
  /// Kills (SIGKILL) and reaps a child that was not waited for.
  ~CleanupChild();
  CleanupChild(const CleanupChild&) = delete;
  CleanupChild& operator=(const CleanupChild&) = delete;

  /// The read end of the child's standard output and error.
  int output_fd() const { return output_fd_; }
  /// Waits for the child to end; returns its wait status (sys/wait.h macros), -1 when
  /// remove_registered_paths killed it.
  int wait();

 private:
  pid_t pid_ = -1;  // -1: reaped
  int output_fd_ = -1;
};

/// Kills the registered children and removes every registered path now (what the signal thread
/// does). For tests.
void remove_registered_paths();

}  // namespace stochnav

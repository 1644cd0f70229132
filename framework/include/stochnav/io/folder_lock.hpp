#pragma once
// One writer per output folder. Two processes writing one --out would leave one run's plot
// beside another's tables; the second is refused instead. The lock is an exclusive flock on
// FOLDER/.stochnav.lock, held while the writer lives and released by the kernel when it dies
// (SIGKILL included), so a dead writer never blocks the next run. The lock file is removed
// when the last holder in this process lets go (docs/reliability.md, "One writer per folder").

#include <filesystem>

namespace stochnav {

class FolderLock final {
 public:
  /// Locks `folder` (which must exist). Throws InputError "FOLDER: another stochnav process is
  /// writing into this folder (...); wait for it to finish or choose another --out" when a
  /// different process holds it, or naming the system's reason when the lock file cannot be
  /// made. Holders in one process nest: a folder locked twice here is locked once.
  explicit FolderLock(const std::filesystem::path& folder);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  /// The lock file's name in a locked folder.
  static constexpr const char* kFileName = ".stochnav.lock";

 private:
  std::filesystem::path key_;  // the folder's canonical path
};

}  // namespace stochnav

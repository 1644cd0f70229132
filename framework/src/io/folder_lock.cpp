#include "stochnav/io/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <mutex>
#include <string>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

struct Held {
  int fd = -1;
  int holders = 0;
  pid_t owner = 0;  // a forked child inherits the map, not the right to write
};

// The folders this process holds: flock locks belong to an open file description, so a second
// open() of the same lock file in this process would conflict with the first.
std::mutex& held_mutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<std::filesystem::path, Held>& held_folders() {
  static std::map<std::filesystem::path, Held> held;
  return held;
}

[[noreturn]] void throw_lock_error(const std::filesystem::path& folder, int errno_value) {
  throw InputError(folder.string() + ": cannot lock the output folder (" +
                   std::strerror(errno_value) + "); choose a writable --out");
}

// Opens and locks FOLDER/.stochnav.lock; returns its descriptor. The file a holder removes
// on release may be the one just opened: a lock taken on a removed file is retried on the new
// one (the path's inode must be the locked descriptor's).
int acquire(const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / FolderLock::kFileName;
  for (;;) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw_lock_error(folder, errno);
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd);
      if (error == EWOULDBLOCK) {
        throw InputError(folder.string() +
                         ": another stochnav process is writing into this folder (it holds " +
                         path.string() + "); wait for it to finish or choose another --out");
      }
      throw_lock_error(folder, error);
    }
    struct stat locked {};
    struct stat named {};
    if (::fstat(fd, &locked) == 0 && ::stat(path.c_str(), &named) == 0 &&
        locked.st_dev == named.st_dev && locked.st_ino == named.st_ino) {
      return fd;
    }
    ::close(fd);  // removed or replaced meanwhile: lock the file that is there now
  }
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& folder) {
  std::error_code error;
  key_ = std::filesystem::canonical(folder, error);
  if (error) throw_lock_error(folder, error.value());
  const std::lock_guard guard(held_mutex());
  Held& held = held_folders()[key_];
  if (held.owner != ::getpid()) held = Held{.owner = ::getpid()};
  if (held.holders == 0) {
    try {
      held.fd = acquire(folder);
    } catch (...) {
      held_folders().erase(key_);
      throw;
    }
  }
  ++held.holders;
}

FolderLock::~FolderLock() {
  const std::lock_guard guard(held_mutex());
  const auto found = held_folders().find(key_);
  if (found == held_folders().end() || --found->second.holders > 0) return;
  // Removed while still locked: a process waiting on this file retries on a new one.
  ::unlink((key_ / kFileName).c_str());
  ::close(found->second.fd);
  held_folders().erase(found);
}

}  // namespace stochnav

#include "stochnav/io/stale_temporaries.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <mutex>
#include <set>
#include <string>
#include <system_error>

namespace stochnav {
namespace {

namespace fs = std::filesystem;

bool decimal_digits_only(std::string_view text) {
  return !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
}

bool process_is_gone(pid_t pid) {
  if (pid <= 0 || pid == ::getpid()) return false;
  return ::kill(pid, 0) == -1 && errno == ESRCH;
}

// Removes `path` when no live writer holds its lock: an exclusive lock is granted only then.
// O_NOFOLLOW and the fstat: a link, a folder or a FIFO of that name is left alone.
void remove_if_unlocked(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return;
  struct stat status {};
  if (::fstat(fd, &status) == 0 && S_ISREG(status.st_mode) && ::flock(fd, LOCK_EX | LOCK_NB) == 0) {
    ::unlink(path.c_str());
  }
  ::close(fd);
}

}  // namespace

std::optional<pid_t> temporary_file_owner(std::string_view file_name) {
  const std::size_t marker = file_name.rfind(".tmp");
  if (marker == std::string_view::npos || marker == 0) return std::nullopt;
  const std::string_view suffix = file_name.substr(marker + 4);
  const std::size_t underscore = suffix.find('_');
  if (underscore == std::string_view::npos) return std::nullopt;
  const std::string_view pid_text = suffix.substr(0, underscore);
  if (!decimal_digits_only(pid_text) || !decimal_digits_only(suffix.substr(underscore + 1))) return std::nullopt;
  pid_t pid = 0;
  const auto [end, error] = std::from_chars(pid_text.data(), pid_text.data() + pid_text.size(), pid);
  if (error != std::errc() || end != pid_text.data() + pid_text.size()) return std::nullopt;
  return pid;
}

int lock_temporary_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd >= 0) ::flock(fd, LOCK_SH);
  return fd;
}

void remove_stale_temporaries(const fs::path& folder) {
  static std::mutex mutex;
  static std::set<fs::path> swept;
  std::error_code error;
  const fs::path key = fs::absolute(folder.empty() ? fs::path(".") : folder, error).lexically_normal();
  {
    const std::lock_guard lock(mutex);
    if (!swept.insert(key).second) return;
  }
  for (fs::directory_iterator entry(key, error); !error && entry != fs::directory_iterator();
       entry.increment(error)) {
    const auto owner = temporary_file_owner(entry->path().filename().string());
    if (owner && process_is_gone(*owner)) remove_if_unlocked(entry->path());
  }
}

}  // namespace stochnav

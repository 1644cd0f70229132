#include "standard_output.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "stochnav/core/errors.hpp"

namespace stochnav::cli {
namespace {

[[noreturn]] void throw_standard_output_error(int errno_value) {
  const std::string reason = errno_value != 0 ? std::strerror(errno_value) : "write error";
  throw InputError("standard output: cannot write (" + reason +
                   "); check the disk space, or that standard output is open and its reader "
                   "is still reading");
}

// Flushes std::cout into stdout and stdout into its descriptor. Returns errno of the failure,
// -1 when an earlier write had failed (its errno is gone), 0 on success.
int flush_both() {
  errno = 0;
  std::cout.flush();
  const bool cout_ok = static_cast<bool>(std::cout);
  const int cout_errno = errno;
  errno = 0;
  if (std::fflush(stdout) != 0) return errno != 0 ? errno : -1;
  if (!cout_ok) return cout_errno != 0 ? cout_errno : -1;
  if (std::ferror(stdout)) return -1;
  return 0;
}

}  // namespace

void reserve_standard_streams() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    // open() returns the lowest free descriptor: this one.
    const int opened = ::open("/dev/null", O_RDONLY | O_NOCTTY);
    if (opened != fd && opened >= 0) ::close(opened);
  }
}

void write_standard_output(std::string_view text) {
  if (const int problem = flush_both(); problem != 0) {
    throw_standard_output_error(problem > 0 ? problem : 0);
  }
  errno = 0;
  const bool written = std::fwrite(text.data(), 1, text.size(), stdout) == text.size();
  if (!written) throw_standard_output_error(errno);
  if (std::fflush(stdout) != 0) throw_standard_output_error(errno);
}

void close_standard_output() {
  const int problem = flush_both();
  // The descriptor, not the FILE: std::cout's destructor-time flush still uses stdout, which
  // holds nothing now; close() is where a delayed write error (NFS) would show.
  errno = 0;
  const bool closed = ::close(STDOUT_FILENO) == 0;
  const int close_errno = errno;
  if (problem != 0) throw_standard_output_error(problem > 0 ? problem : 0);
  if (!closed) throw_standard_output_error(close_errno);
}

}  // namespace stochnav::cli

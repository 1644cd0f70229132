#include "stochnav/io/output_target.hpp"

#include <string>
#include <system_error>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;

// The kernel's own limit on links followed in one path (MAXSYMLINKS).
constexpr int kMaxLinks = 40;

[[noreturn]] void refuse(const fs::path& path, const std::string& what) {
  throw InputError(path.string() + ": is " + what +
                   "; an output must be a regular file, a FIFO or a character device: choose "
                   "another output path");
}

// The final target of a chain of symbolic links starting at `path` (the path itself when it is
// not a link). A link's relative target is relative to the link's folder.
fs::path follow_links(const fs::path& path) {
  fs::path current = path;
  for (int links = 0;; ++links) {
    std::error_code error;
    if (fs::symlink_status(current, error).type() != fs::file_type::symlink) return current;
    if (links == kMaxLinks) {
      throw InputError(path.string() + ": more than " + std::to_string(kMaxLinks) +
                       " symbolic links in a chain (a loop?); fix the links or choose another "
                       "output path");
    }
    const fs::path target = fs::read_symlink(current, error);
    if (error) return current;  // unreadable link: the write will say why
    current = target.is_absolute() ? target : current.parent_path() / target;
  }
}

}  // namespace

OutputTarget resolve_output_target(const fs::path& path) {
  std::error_code error;
  // The kernel's view first (it follows "magic" links such as /dev/stdout -> /proc/self/fd/1,
  // whose text may be "pipe:[1234]"): a FIFO or a device is written through the path as given.
  const fs::file_status status = fs::status(path, error);
  switch (status.type()) {
    case fs::file_type::fifo:
    case fs::file_type::character:
      return {path, true};
    case fs::file_type::directory:
      refuse(path, "a folder");
    case fs::file_type::socket:
      refuse(path, "a socket");
    case fs::file_type::block:
      refuse(path, "a block device");
    default:
      break;
  }
  // A regular file, nothing yet, or a dangling link: the file at the end of the links, replaced.
  return {follow_links(path), false};
}

}  // namespace stochnav

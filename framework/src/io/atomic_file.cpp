#include "stochnav/io/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/temporary_files.hpp"
#include "stochnav/io/output_target.hpp"
#include "stochnav/io/stale_temporaries.hpp"

namespace stochnav {
namespace {

std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  return temporary;
}

}  // namespace

void throw_write_error(const std::filesystem::path& path, int errno_value) {
  const std::string reason = errno_value != 0 ? std::strerror(errno_value) : "write failed";
  throw InputError(path.string() + ": cannot write (" + reason +
                   "); check the space and permissions of the output folder");
}

PendingFile::PendingFile(std::filesystem::path path) {
  OutputTarget target = resolve_output_target(path);
  final_ = std::move(target.path);
  in_place_ = target.in_place;
  if (in_place_) {
    temporary_ = final_;
    return;
  }
  remove_stale_temporaries(final_.parent_path());
  temporary_ = temporary_beside(final_);
  registration_.emplace(temporary_);
  std::error_code error;
  create_file_before_cleanup(temporary_, error);
  if (error) throw_write_error(final_, error.value());
  lock_fd_ = lock_temporary_file(temporary_);
}

// Opened before the signal cleanup or never (the thread then waits for the process to end),
// and without O_CREAT ("r+"): a temporary file the cleanup removed stays removed. In place:
// opened for writing outside the cleanup's lock (a FIFO's open waits for its reader).
std::ofstream PendingFile::open_stream() const {
  std::ofstream out;
  int open_errno = 0;
  if (in_place_) {
    out.open(final_, std::ios::out | std::ios::binary);
    if (!out) throw_write_error(final_, errno);
    return out;
  }
  run_before_cleanup([&] {
    out.open(temporary_, std::ios::in | std::ios::out | std::ios::binary);
    open_errno = errno;
  });
  if (!out) throw_write_error(final_, open_errno);
  return out;
}

std::FILE* PendingFile::open_file() const {
  std::FILE* out = nullptr;
  int open_errno = 0;
  if (in_place_) {
    out = std::fopen(final_.c_str(), "wb");
    if (out == nullptr) throw_write_error(final_, errno);
    return out;
  }
  run_before_cleanup([&] {
    out = std::fopen(temporary_.c_str(), "r+b");
    open_errno = errno;
  });
  if (out == nullptr) throw_write_error(final_, open_errno);
  return out;
}

PendingFile::~PendingFile() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
  if (!committed_ && !in_place_) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void PendingFile::commit() {
  if (in_place_) {
    committed_ = true;
    return;
  }
  std::error_code error;
  // A file replaced keeps its permission bits (as `sed -i` does; set now, as they may forbid
  // the writing above); a new one has the umask's.
  const std::filesystem::file_status existing = std::filesystem::status(final_, error);
  if (!error && std::filesystem::is_regular_file(existing)) {
    std::filesystem::permissions(temporary_, existing.permissions(), error);
  }
  std::filesystem::rename(temporary_, final_, error);
  if (error) {
    throw InputError(final_.string() + ": cannot write (" + error.message() +
                     "); check that the folder exists and is writable");
  }
  committed_ = true;
  registration_->release();
}

void write_pending_file(const PendingFile& pending, std::string_view content) {
  std::FILE* out = pending.open_file();
  const bool written = std::fwrite(content.data(), 1, content.size(), out) == content.size() &&
                       std::fflush(out) == 0;
  const int write_errno = errno;
  const bool closed = std::fclose(out) == 0;
  if (!written) throw_write_error(pending.final_path(), write_errno);
  if (!closed) throw_write_error(pending.final_path(), errno);
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  PendingFile pending(path);
  write_pending_file(pending, content);
  pending.commit();
}

OutputFolder::OutputFolder(std::filesystem::path path) : path_(std::move(path)) {
  std::error_code error;
  // The outermost missing folder: what removing "what we created" means.
  std::filesystem::path probe = std::filesystem::absolute(path_, error);
  std::filesystem::path outermost_missing;
  while (!probe.empty() && !std::filesystem::exists(probe, error)) {
    outermost_missing = probe;
    if (probe == probe.parent_path()) break;
    probe = probe.parent_path();
  }
  // Registered before it exists: a signal's cleanup between making and registering would
  // otherwise leave it behind (removing a path not yet made is harmless).
  if (!outermost_missing.empty()) {
    created_ = outermost_missing;
    registration_ = std::make_unique<TemporaryPath>(created_);
  }
  create_directories_before_cleanup(path_, error);
  if (error || !std::filesystem::is_directory(path_)) {
    const std::string reason = error ? error.message() : "a file of that name exists";
    throw InputError(path_.string() + ": cannot create the output folder (" + reason +
                     "); choose a writable --out");
  }
  try {
    lock_.emplace(path_);
  } catch (...) {
    if (!created_.empty()) std::filesystem::remove_all(created_, error);
    throw;
  }
}

OutputFolder::~OutputFolder() {
  if (created_.empty()) return;
  std::error_code ignored;
  std::filesystem::remove_all(created_, ignored);
}

void OutputFolder::keep() {
  created_.clear();
  registration_.reset();
}

}  // namespace stochnav

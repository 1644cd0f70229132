#include "stochnav/io/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  return temporary;
}

}  // namespace

PendingFile::PendingFile(std::filesystem::path path)
    : final_(std::move(path)), temporary_(temporary_beside(final_)) {}

PendingFile::~PendingFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void PendingFile::commit() {
  std::error_code error;
  std::filesystem::rename(temporary_, final_, error);
  if (error) {
    throw InputError(final_.string() + ": cannot write (" + error.message() +
                     "); check that the folder exists and is writable");
  }
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  PendingFile pending(path);
  {
    std::ofstream out(pending.temporary_path(), std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) {
      throw InputError(path.string() + ": cannot write (folder missing or not writable); " +
                       "check the output path");
    }
  }
  pending.commit();
}

}  // namespace stochnav

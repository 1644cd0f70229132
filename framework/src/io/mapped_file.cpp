#include "stochnav/io/mapped_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "stochnav/core/errors.hpp"

namespace stochnav {

MappedFile::MappedFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    throw InputError(path + ": cannot open file (" + std::strerror(errno) +
                     "); check the path given with --input");
  }
  struct stat status {};
  if (::fstat(fd, &status) != 0) {
    const int error = errno;
    ::close(fd);
    throw InputError(path + ": cannot read file size (" + std::strerror(error) + ")");
  }
  size_ = static_cast<std::size_t>(status.st_size);
  if (size_ > 0) {
    void* address = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (address == MAP_FAILED) {
      const int error = errno;
      ::close(fd);
      throw InputError(path + ": cannot map file (" + std::strerror(error) + ")");
    }
    data_ = static_cast<const std::byte*>(address);
    ::madvise(address, size_, MADV_SEQUENTIAL);  // read ahead generously
  }
  ::close(fd);  // the mapping keeps the file
}

MappedFile::~MappedFile() {
  if (data_ != nullptr) ::munmap(const_cast<std::byte*>(data_), size_);
}

void MappedFile::release(std::size_t offset, std::size_t size) const {
  if (data_ == nullptr || offset >= size_) return;
  const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  const std::size_t end = std::min(size_, offset + size);
  const std::size_t first = (offset + page - 1) / page * page;
  // The last, partial page of the file counts as whole.
  const std::size_t last = end == size_ ? (end + page - 1) / page * page : end / page * page;
  if (last <= first) return;
  ::madvise(const_cast<std::byte*>(data_) + first, last - first, MADV_DONTNEED);
}

}  // namespace stochnav

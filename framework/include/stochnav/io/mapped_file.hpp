#pragma once
// A whole file mapped read-only into memory: the bytes are the page cache's, not a copy.

#include <cstddef>
#include <span>
#include <string>

namespace stochnav {

class MappedFile final {
 public:
  /// Maps `path` read-only. Throws InputError naming the file when it cannot be opened or
  /// mapped. An empty file gives an empty span.
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::span<const std::byte> bytes() const { return {data_, size_}; }

  /// Tells the kernel the bytes [offset, offset + size) will not be read again: their pages
  /// leave this process's resident memory (they stay in the page cache; a later read maps them
  /// back). Only whole pages inside the range are released. A hint: errors are ignored.
  void release(std::size_t offset, std::size_t size) const;

 private:
  const std::byte* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace stochnav

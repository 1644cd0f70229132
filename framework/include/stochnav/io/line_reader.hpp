#pragma once
// Reads a text file, plain or gzip-compressed (".gz"), line by line in large chunks.

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace stochnav {

/// Throws InputError when `path` names a folder ("PATH: is a folder, not a record file; ..."):
/// reading one gave "read error".
void refuse_folder(const std::string& path);

class LineReader final {
 public:
  /// Opens `path`; throws InputError if it cannot be read, or if a ".gz" file has no gzip
  /// header. A ".gz" file is checked to its end: next() throws InputError naming the file when
  /// the data are corrupt or the file ends early (truncated), instead of ending the lines.
  explicit LineReader(const std::string& path);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  /// Sets `line` to the next line without its line terminator ("\n" or "\r\n"). The view is
  /// valid until the next call. Returns false at the end of the file. A UTF-8 byte-order mark
  /// before the first line is dropped; CR-only line endings (a CR inside the first line) throw
  /// InputError.
  bool next(std::string_view& line);
  /// Bytes of the file consumed by the lines returned so far (uncompressed files: the file offset
  /// where the next line starts).
  std::size_t consumed_bytes() const { return bytes_read_ - (end_ - begin_); }
  /// True for a plain (not gzip-compressed) file.
  bool plain() const { return file_ != nullptr; }
  /// 1-based number of the line last returned.
  std::size_t line_number() const { return line_number_; }
  const std::string& path() const { return path_; }

 private:
  std::size_t fill();  // reads more bytes after the unconsumed tail; returns bytes read

  std::string path_;
  void* gz_ = nullptr;          // gzFile when compressed
  std::FILE* file_ = nullptr;   // plain file otherwise
  std::vector<char> buffer_;
  std::size_t begin_ = 0;  // first unconsumed byte
  std::size_t end_ = 0;    // one past the last valid byte
  bool eof_ = false;
  std::size_t line_number_ = 0;
  std::size_t bytes_read_ = 0;  // bytes taken from the file (after decompression)
};

}  // namespace stochnav

#include "stochnav/io/line_reader.hpp"

#include <zlib.h>

#include <cerrno>
#include <filesystem>
#include <cstring>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

constexpr std::size_t kChunkBytes = 1 << 20;

// zlib's state after a read: a truncated or corrupt stream is an error naming the file and the
// fault, never the end of the record (zlib hands out what it decompressed before the fault).
void check_gzip_state(gzFile gz, const std::string& path) {
  int code = Z_OK;
  const char* message = gzerror(gz, &code);
  if (code == Z_OK) return;
  std::string detail = message != nullptr && *message != '\0' ? message : "zlib error";
  // zlib's message starts with the path it was opened with; ours names the file once.
  if (detail.starts_with(path + ": ")) detail.erase(0, path.size() + 2);
  if (code == Z_BUF_ERROR) {
    throw InputError(path + ": truncated gzip file (" + detail +
                     "): the record is incomplete; copy or download it again");
  }
  if (code == Z_ERRNO) {
    throw InputError(path + ": read error (" + std::strerror(errno) + "); check the file");
  }
  throw InputError(path + ": corrupt gzip data (" + detail +
                   "); copy or download the record again, or re-create the .gz file");
}

}  // namespace

void refuse_folder(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path + ": is a folder, not a record file; give the file itself, not the "
                     "folder that holds it");
  }
}

LineReader::LineReader(const std::string& path) : path_(path), buffer_(kChunkBytes) {
  refuse_folder(path);
  if (path.ends_with(".gz")) {
    gz_ = gzopen(path.c_str(), "rb");
    if (gz_ != nullptr) gzbuffer(static_cast<gzFile>(gz_), 1 << 17);
  } else {
    file_ = std::fopen(path.c_str(), "rb");
  }
  if (gz_ == nullptr && file_ == nullptr) {
    throw InputError(path + ": cannot open file (" + std::strerror(errno) +
                     "); check the path given with --input");
  }
  // zlib reads a file without a gzip header as it is ("transparent" mode): a damaged header
  // would otherwise be parsed as text. gzdirect() looks at the first bytes.
  if (gz_ != nullptr && gzdirect(static_cast<gzFile>(gz_)) != 0) {
    gzclose(static_cast<gzFile>(gz_));
    gz_ = nullptr;
    throw InputError(path + ": not a gzip file (no gzip header); decompress it with gzip, or "
                     "rename it without .gz if it is plain text");
  }
}

LineReader::~LineReader() {
  if (gz_ != nullptr) gzclose(static_cast<gzFile>(gz_));
  if (file_ != nullptr) std::fclose(file_);
}

std::size_t LineReader::fill() {
  // Keep the unconsumed tail (a partial line) at the front, grow if one line fills the buffer.
  const std::size_t tail = end_ - begin_;
  if (begin_ > 0) std::memmove(buffer_.data(), buffer_.data() + begin_, tail);
  begin_ = 0;
  end_ = tail;
  if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);
  const std::size_t room = buffer_.size() - end_;
  std::size_t got = 0;
  if (gz_ != nullptr) {
    const int n = gzread(static_cast<gzFile>(gz_), buffer_.data() + end_,
                         static_cast<unsigned>(room));
    check_gzip_state(static_cast<gzFile>(gz_), path_);
    if (n < 0) throw InputError(path_ + ": corrupt gzip data; re-create the .gz file");
    got = static_cast<std::size_t>(n);
  } else {
    got = std::fread(buffer_.data() + end_, 1, room, file_);
    if (got == 0 && std::ferror(file_)) throw InputError(path_ + ": read error");
  }
  end_ += got;
  bytes_read_ += got;
  if (got == 0) eof_ = true;
  return got;
}

namespace {

// The first line: a UTF-8 byte-order mark (what some Windows editors put first) is not part of
// it, and a carriage return inside it means old Mac line endings (CR alone), which would make
// the whole file one line. CRLF endings are handled in next().
std::string_view checked_first_line(std::string_view line, const std::string& path) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (line.substr(0, kBom.size()) == kBom) line.remove_prefix(kBom.size());
  if (line.find('\r') != std::string_view::npos) {
    throw InputError(path + ":1: carriage return (CR) inside the line: the file has CR-only "
                     "line endings; convert it to LF or CRLF line endings");
  }
  return line;
}

}  // namespace

bool LineReader::next(std::string_view& line) {
  while (true) {
    const char* start = buffer_.data() + begin_;
    const auto* newline =
        static_cast<const char*>(std::memchr(start, '\n', end_ - begin_));
    if (newline != nullptr) {
      std::size_t length = static_cast<std::size_t>(newline - start);
      begin_ += length + 1;
      if (length > 0 && start[length - 1] == '\r') --length;
      ++line_number_;
      line = std::string_view(start, length);
      if (line_number_ == 1) line = checked_first_line(line, path_);
      return true;
    }
    if (eof_ || fill() == 0) {
      if (begin_ == end_) return false;
      // Last line without a terminator.
      const char* rest = buffer_.data() + begin_;
      std::size_t length = end_ - begin_;
      if (rest[length - 1] == '\r') --length;
      begin_ = end_;
      ++line_number_;
      line = std::string_view(rest, length);
      if (line_number_ == 1) line = checked_first_line(line, path_);
      return true;
    }
  }
}

}  // namespace stochnav

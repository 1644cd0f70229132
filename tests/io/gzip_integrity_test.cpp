// Issue #26: a .gz record is checked to its end. A truncated or corrupt file is an error naming
// the file and the fault, never a shorter record nor "row has 1 cells".

#include <gtest/gtest.h>
#include <zlib.h>

#include <functional>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/record.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::TempDir;

// 2,000 samples of a one-column text record, gzip-compressed in memory.
std::string gzip_record() {
  std::string text = "# a rate record\n";
  for (int i = 0; i < 2000; ++i) text += std::to_string((i * 37) % 101 - 50) + "\n";
  z_stream stream{};
  deflateInit2(&stream, Z_BEST_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&stream, text.size()), '\0');
  stream.next_in = reinterpret_cast<Bytef*>(text.data());
  stream.avail_in = static_cast<uInt>(text.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

struct GzipCase {
  std::string name;
  std::function<std::string(std::string)> damage;  ///< applied to the whole .gz file
  std::string fragment;                            ///< in the message; empty: no error
  std::size_t samples = 0;                         ///< read when there is no error
};
void PrintTo(const GzipCase& c, std::ostream* os) { *os << c.name; }

class GzipIntegrity : public ::testing::TestWithParam<GzipCase> {};

TEST_P(GzipIntegrity, CheckedToTheEnd) {
  const GzipCase& c = GetParam();
  TempDir dir;
  ReadOptions options;
  options.path = dir.write("record.txt.gz", c.damage(gzip_record()));
  options.rate_hz = 100.0;
  if (c.fragment.empty()) {
    EXPECT_EQ(read_record(options).values.size(), c.samples);
    return;
  }
  try {
    const Record record = read_record(options);
    FAIL() << "read " << record.values.size() << " samples of a damaged file";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find("record.txt.gz: "), std::string::npos) << message;
    EXPECT_NE(message.find(c.fragment), std::string::npos) << message;
  }
}

std::string flip(std::string bytes, std::size_t from_end) {
  bytes[bytes.size() - from_end] = static_cast<char>(bytes[bytes.size() - from_end] ^ 0x55);
  return bytes;
}

INSTANTIATE_TEST_SUITE_P(
    Issue26, GzipIntegrity,
    ::testing::Values(
        GzipCase{"intact", [](std::string b) { return b; }, "", 2000},
        GzipCase{"concatenated_members_are_one_stream",
                 [](std::string b) {
                   // gzip allows members back to back: `cat a.gz b.gz` is 4000 samples.
                   return b + b;
                 },
                 "", 4000},
        GzipCase{"truncated_in_the_data",
                 [](std::string b) { return b.substr(0, b.size() / 3); }, "truncated gzip file"},
        GzipCase{"truncated_trailer",
                 [](std::string b) { return b.substr(0, b.size() - 4); }, "truncated gzip file"},
        GzipCase{"header_only", [](std::string b) { return b.substr(0, 10); },
                 "truncated gzip file"},
        GzipCase{"crc_wrong", [](std::string b) { return flip(b, 6); }, "corrupt gzip data"},
        GzipCase{"length_wrong", [](std::string b) { return flip(b, 2); }, "corrupt gzip data"},
        GzipCase{"data_corrupt",
                 [](std::string b) {
                   for (std::size_t i = 20; i < 40; ++i) b[i] = static_cast<char>(0xff);
                   return b;
                 },
                 "corrupt gzip data"},
        GzipCase{"header_corrupt",
                 [](std::string b) {
                   b[0] = 'x';
                   return b;
                 },
                 "not a gzip file"},
        GzipCase{"plain_text_named_gz", [](std::string) { return std::string("1\n2\n3\n4\n"); },
                 "not a gzip file"}),
    [](const ::testing::TestParamInfo<GzipCase>& case_info) { return case_info.param.name; });

}  // namespace
}  // namespace stochnav

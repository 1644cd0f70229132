#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/io/sample_reader.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::TempDir;

ReadOptions options_for(const std::string& path) {
  ReadOptions options;
  options.path = path;
  return options;
}

// Expects InputError whose message contains every fragment.
template <typename Error = InputError>
void expect_error(const ReadOptions& options, std::vector<std::string> fragments) {
  try {
    read_record(options);
    FAIL() << "no error for " << options.path;
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    for (const auto& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos) << message << " lacks " << fragment;
    }
  }
}

TEST(ReadRecord, CsvByNameWithTimeColumnDerivesRate) {
  TempDir dir;
  const auto path = dir.write("a.csv", "t,gx,gy\n0.00,1,2\n0.01,3,4\n0.02,5,6\n0.03,7,8\n");
  auto options = options_for(path);
  options.column = "gy";
  const Record record = read_record(options);
  EXPECT_EQ(record.values, (std::vector<double>{2, 4, 6, 8}));
  EXPECT_NEAR(record.rate_hz, 100.0, 1e-9);
  EXPECT_EQ(record.column, "gy");
}

TEST(ReadRecord, CsvByIndexAndDefaultColumnSkipsTime) {
  TempDir dir;
  const auto path = dir.write("a.csv", "t_s,gx,gy\r\n0,1,2\r\n1,3,4\r\n");
  auto options = options_for(path);
  EXPECT_EQ(read_record(options).values, (std::vector<double>{1, 3}));
  options.column = "2";
  EXPECT_EQ(read_record(options).values, (std::vector<double>{2, 4}));
}

TEST(ReadRecord, Stable32TextWithComments) {
  TempDir dir;
  const auto path = dir.write("p.dat", "# header\n#\n 1.5e-3\n\n-2.0e-3   \n3\n");
  auto options = options_for(path);
  options.rate_hz = 1.0;
  options.kind = DataKind::kPhase;
  const Record record = read_record(options);
  EXPECT_EQ(record.values, (std::vector<double>{1.5e-3, -2.0e-3, 3}));
  EXPECT_EQ(record.kind, DataKind::kPhase);
}

TEST(ReadRecord, InterleavedBinaryChannels) {
  TempDir dir;
  const std::vector<double> epochs{1, 10, 2, 20, 3, 30};
  std::string bytes(epochs.size() * 8, '\0');
  std::memcpy(bytes.data(), epochs.data(), bytes.size());
  const auto path = dir.write("r.f64", bytes);
  auto options = options_for(path);
  options.rate_hz = 10.0;
  options.binary_channels = 2;
  options.column = "1";
  EXPECT_EQ(read_record(options).values, (std::vector<double>{10, 20, 30}));

  const std::vector<float> narrow{0.5F, 1.5F};
  std::string narrow_bytes(8, '\0');
  std::memcpy(narrow_bytes.data(), narrow.data(), 8);
  auto float_options = options_for(dir.write("r.f32", narrow_bytes));
  float_options.rate_hz = 1.0;
  EXPECT_EQ(read_record(float_options).values, (std::vector<double>{0.5, 1.5}));
}

TEST(ReadRecord, StreamsInBlocks) {
  TempDir dir;
  std::string text = "t,x\n";
  for (int i = 0; i < 1000; ++i) text += std::to_string(i * 0.5) + "," + std::to_string(i) + "\n";
  SampleReader reader(options_for(dir.write("s.csv", text)));
  std::vector<double> block;
  std::size_t blocks = 0;
  while (reader.read_block(block, 64) > 0) ++blocks;
  EXPECT_EQ(blocks, 16U);
  EXPECT_EQ(block.size(), 1000U);
  EXPECT_NEAR(reader.rate_hz(), 2.0, 1e-12);
}

TEST(ReadRecordErrors, EmptyFile) {
  TempDir dir;
  auto options = options_for(dir.write("e.csv", ""));
  expect_error(options, {"e.csv", "no samples"});
  options = options_for(dir.write("c.txt", "# only comments\n"));
  options.rate_hz = 1;
  expect_error(options, {"c.txt", "no samples"});
}

TEST(ReadRecordErrors, OneSample) {
  TempDir dir;
  auto options = options_for(dir.write("one.csv", "t,x\n0,1\n"));
  expect_error(options, {"one.csv", "only one sample"});
}

TEST(ReadRecordErrors, NonNumericCellNamesLine) {
  TempDir dir;
  auto options = options_for(dir.write("bad.csv", "t,x\n0,1\n1,abc\n2,3\n"));
  expect_error(options, {"bad.csv:3", "'abc'", "not a number"});
}

TEST(ReadRecordErrors, NanNamesLine) {
  TempDir dir;
  auto options = options_for(dir.write("nan.csv", "t,x\n0,1\n1,2\n2,nan\n"));
  expect_error(options, {"nan.csv:4", "NaN"});
  std::string bytes(16, '\0');
  const double values[2] = {1.0, std::nan("")};
  std::memcpy(bytes.data(), values, 16);
  auto binary = options_for(dir.write("nan.f64", bytes));
  binary.rate_hz = 1;
  expect_error(binary, {"nan.f64", "epoch 1", "NaN"});
}

TEST(ReadRecordErrors, MissingColumnListsColumns) {
  TempDir dir;
  auto options = options_for(dir.write("m.csv", "t,gx\n0,1\n1,2\n"));
  options.column = "gz";
  expect_error(options, {"m.csv:1", "'gz'", "t, gx"});
  options.column = "5";
  expect_error(options, {"m.csv:1", "out of range"});
}

TEST(ReadRecordErrors, RaggedRow) {
  TempDir dir;
  auto options = options_for(dir.write("r.csv", "t,x,y\n0,1,2\n1,2\n"));
  expect_error(options, {"r.csv:3", "2 cells"});
}

TEST(ReadRecordErrors, NonUniformTime) {
  TempDir dir;
  auto options = options_for(dir.write("g.csv", "t,x\n0,1\n1,2\n2,3\n4,4\n5,5\n"));
  expect_error(options, {"g.csv:5", "not uniformly sampled"});
}

TEST(ReadRecordErrors, DecreasingTime) {
  TempDir dir;
  auto options = options_for(dir.write("d.csv", "t,x\n0,1\n1,2\n0.5,3\n"));
  expect_error(options, {"d.csv:4", "does not increase"});
}

TEST(ReadRecordErrors, NoRateAndNoTime) {
  TempDir dir;
  auto options = options_for(dir.write("n.txt", "1\n2\n3\n"));
  expect_error<ConfigError>(options, {"n.txt", "--rate"});
}

TEST(ReadRecordErrors, RateDisagreesWithTimeColumn) {
  TempDir dir;
  auto options = options_for(dir.write("x.csv", "t,x\n0,1\n0.01,2\n0.02,3\n"));
  options.rate_hz = 50.0;
  expect_error(options, {"x.csv", "disagrees"});
}

TEST(ReadRecordErrors, MissingFileAndBadBinarySize) {
  TempDir dir;
  expect_error(options_for(dir.file("absent.csv")), {"absent.csv", "cannot open"});
  auto options = options_for(dir.write("odd.f64", std::string(12, '\0')));
  options.rate_hz = 1;
  expect_error(options, {"odd.f64", "not a whole number of epochs"});
}

}  // namespace
}  // namespace stochnav

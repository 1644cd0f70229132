// The IMU input of navigation runs: the reader thread (experiment/background_imu_reader.hpp)
// serves exactly what ImuFileReader reads, in order, with a bad row's error at its place; the
// shared records of compare (shared_imu_records.hpp) are read once per seed and dropped after
// the seed's last run.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "records/shared_imu_records.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/background_imu_reader.hpp"
#include "stochnav/experiment/imu_record.hpp"
#include "stochnav/experiment/imu_stream.hpp"
#include "stochnav/experiment/navigation_files.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::TempDir;

// Rows of rates (the reader scales them by dt) spanning several of the reader's blocks.
std::string rate_file(std::size_t rows, std::size_t bad_row = 0) {
  std::string text = "t,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
  for (std::size_t k = 1; k <= rows; ++k) {
    if (k == bad_row) {
      text += "oops,0,0,0,0,0,0\n";
      continue;
    }
    const double x = static_cast<double>(k);
    std::ostringstream row;
    row.precision(17);
    row << 0.01 * x << ',' << 1e-5 * x << ",-2e-5,3e-5,0.1,-0.2," << 9.8 + 1e-6 * x << '\n';
    text += row.str();
  }
  return text;
}

void expect_same(const ImuIncrement& a, const ImuIncrement& b) {
  EXPECT_EQ(a.t_s, b.t_s);
  EXPECT_EQ(a.dt_s, b.dt_s);
  EXPECT_EQ(a.delta_theta_b, b.delta_theta_b);
  EXPECT_EQ(a.delta_v_b, b.delta_v_b);
}

TEST(BackgroundImuReader, ServesWhatTheFileReaderReads) {
  const TempDir dir;
  const std::size_t rows = 3 * BackgroundImuReader::kBlockEpochs + 17;
  const std::string path = dir.write("imu.csv", rate_file(rows));
  ImuFileReader direct(path);
  BackgroundImuReader threaded(path);
  EXPECT_EQ(threaded.rate_hz(), direct.rate_hz());
  EXPECT_EQ(threaded.start_time_s(), direct.start_time_s());
  ImuIncrement a, b;
  std::size_t count = 0;
  while (direct.next(a)) {
    ASSERT_TRUE(threaded.next(b));
    expect_same(a, b);
    ++count;
  }
  EXPECT_EQ(count, rows);
  EXPECT_FALSE(threaded.next(b));
  EXPECT_FALSE(threaded.next(b));
}

TEST(BackgroundImuReader, ThrowsABadRowAfterTheRowsBeforeIt) {
  const TempDir dir;
  const std::size_t bad_row = BackgroundImuReader::kBlockEpochs + 100;
  const std::string path = dir.write("imu.csv", rate_file(2 * bad_row, bad_row));
  BackgroundImuReader reader(path);
  ImuIncrement increment;
  for (std::size_t k = 1; k < bad_row; ++k) ASSERT_TRUE(reader.next(increment)) << k;
  try {
    reader.next(increment);
    FAIL() << "no error at the bad row";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("imu.csv:" + std::to_string(bad_row + 1) + ":"),
              std::string::npos)
        << error.what();
  }
}

TEST(BackgroundImuReader, StopsWhenTheRunEndsEarly) {
  const TempDir dir;
  const std::string path = dir.write("imu.csv", rate_file(20 * BackgroundImuReader::kBlockEpochs));
  BackgroundImuReader reader(path);
  ImuIncrement increment;
  ASSERT_TRUE(reader.next(increment));
  // The destructor stops the thread while it waits for room in the queue (no hang).
}

TEST(SharedImuRecords, OneParsedCopyPerSeedDroppedAfterItsLastRun) {
  const TempDir dir;
  const std::string path = dir.write("imu.csv", rate_file(1000));
  SharedImuRecords records(/*seeds=*/2, /*runs_per_seed=*/2);
  std::weak_ptr<const ImuRecord> watched;
  {
    const SharedImuRecords::Lease first = records.lease(0, path);
    ASSERT_TRUE(first.record());
    watched = first.record();
    {
      const SharedImuRecords::Lease second = records.lease(0, path);
      EXPECT_EQ(second.record(), first.record());
    }
    EXPECT_EQ(first.record()->epochs.size(), 1000u);
    ImuStream stream(first.record());
    ImuFileReader direct(path);
    ImuIncrement a, b;
    while (direct.next(a)) {
      ASSERT_TRUE(stream.next(b));
      expect_same(a, b);
    }
    EXPECT_FALSE(stream.next(b));
  }
  EXPECT_TRUE(watched.expired());
}

TEST(SharedImuRecords, OverTheBudgetRunsStreamTheFile) {
  const TempDir dir;
  const std::string path = dir.write("imu.csv", rate_file(1000));
  SharedImuRecords records(1, 2, /*budget_bytes=*/1000 * sizeof(ImuIncrement) / 2);
  const SharedImuRecords::Lease lease = records.lease(0, path);
  EXPECT_FALSE(lease.record());
}

}  // namespace
}  // namespace stochnav

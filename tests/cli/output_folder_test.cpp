// Issue #26, folders: a command writing into a folder another process is writing into exits 2
// with one line and leaves that folder as it was; a run into a folder that held an earlier run
// leaves none of the earlier run's files beside its own.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "run_cli.hpp"
#include "stochnav/io/folder_lock.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;
using testing::TempDir;

std::string short_scenario(const TempDir& dir) {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) + "/configs/scenarios/drilling_short.json");
  return dir.write("scenario.json", std::string(std::istreambuf_iterator<char>(in), {}));
}

TEST(OutputFolderCli, AFolderAnotherProcessWritesIsRefused) {
  const TempDir dir;
  const fs::path out = dir.path() / "busy";
  fs::create_directories(out);
  const std::string earlier = dir.write("busy/imu.csv", "another run's half-written record");
  const std::string scenario = short_scenario(dir);
  {
    const FolderLock other_writer(out);  // this test process stands for the other stochnav
    const auto result =
        run_cli("simulate scenario '" + scenario + "' --out '" + out.string() + "'", dir.path());
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
    EXPECT_NE(result.err.find("another stochnav process is writing into this folder"),
              std::string::npos)
        << result.err;
    std::ifstream kept(earlier);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}),
              "another run's half-written record");
  }
  // The writer gone, the same command runs, and leaves no lock file behind.
  const auto result =
      run_cli("simulate scenario '" + scenario + "' --out '" + out.string() + "'", dir.path());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(fs::exists(out / FolderLock::kFileName));
}

}  // namespace
}  // namespace stochnav

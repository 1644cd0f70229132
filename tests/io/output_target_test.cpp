// Issue #26: where an output goes (io/output_target.hpp). A regular file is replaced atomically;
// a link is followed and stays; a FIFO or a character device is written in place; a folder or a
// socket is refused. And stale temporary files of dead processes are removed by the next writer.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/io/output_target.hpp"
#include "stochnav/io/stale_temporaries.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::size_t entries(const fs::path& folder) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder), {}));
}

std::string message_of(const fs::path& path) {
  try {
    write_file_atomically(path, "text\n");
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

TEST(OutputTarget, RegularFileIsReplacedAtomicallyKeepingItsMode) {
  TempDir dir;
  const fs::path file = dir.write("out.csv", "old\n");
  fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  write_file_atomically(file, "new\n");
  EXPECT_EQ(contents(file), "new\n");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(file)));
  EXPECT_EQ(fs::status(file).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(entries(dir.path()), 1u);
}

TEST(OutputTarget, SymlinkIsFollowedAndStays) {
  TempDir dir;
  fs::create_directories(dir.path() / "data");
  const fs::path target = dir.write("data/out.csv", "old\n");
  const fs::path link = dir.path() / "link.csv";
  fs::create_symlink("data/out.csv", link);  // relative to the link's folder
  const fs::path chain = dir.path() / "chain.csv";
  fs::create_symlink(link, chain);

  write_file_atomically(chain, "new\n");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_TRUE(fs::is_symlink(chain));
  EXPECT_EQ(contents(target), "new\n");
  EXPECT_EQ(entries(dir.path() / "data"), 1u) << "no temporary file left beside the target";
  EXPECT_EQ(resolve_output_target(chain).path, target);
  EXPECT_FALSE(resolve_output_target(chain).in_place);
}

TEST(OutputTarget, DanglingSymlinkGetsItsTargetCreated) {
  TempDir dir;
  const fs::path link = dir.path() / "link.csv";
  fs::create_symlink(dir.path() / "new.csv", link);
  write_file_atomically(link, "new\n");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(contents(dir.path() / "new.csv"), "new\n");
}

TEST(OutputTarget, SymlinkLoopIsRefused) {
  TempDir dir;
  fs::create_symlink(dir.path() / "b", dir.path() / "a");
  fs::create_symlink(dir.path() / "a", dir.path() / "b");
  const std::string message = message_of(dir.path() / "a");
  EXPECT_NE(message.find("symbolic links in a chain"), std::string::npos) << message;
}

TEST(OutputTarget, FifoIsWrittenInPlace) {
  TempDir dir;
  const fs::path fifo = dir.path() / "out.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string read;
  std::thread reader([&] { read = contents(fifo); });
  write_file_atomically(fifo, "through the pipe\n");
  reader.join();
  EXPECT_EQ(read, "through the pipe\n");
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);
  EXPECT_EQ(entries(dir.path()), 1u);
}

TEST(OutputTarget, CharacterDeviceIsWrittenInPlace) {
  TempDir dir;
  const fs::path device = dir.path() / "null";
  // A null device of our own (root only): the test must not risk the system's /dev/null.
  if (::mknod(device.c_str(), S_IFCHR | 0600, ::makedev(1, 3)) != 0) {
    GTEST_SKIP() << "cannot make a device node here (not root, or no CAP_MKNOD)";
  }
  write_file_atomically(device, "gone\n");
  EXPECT_EQ(fs::status(device).type(), fs::file_type::character);
  EXPECT_EQ(entries(dir.path()), 1u);
  PendingFile pending(device);
  EXPECT_TRUE(pending.in_place());
  EXPECT_EQ(pending.temporary_path(), device);
}

TEST(OutputTarget, FolderAndSocketAreRefused) {
  TempDir dir;
  fs::create_directories(dir.path() / "folder");
  EXPECT_EQ(message_of(dir.path() / "folder"),
            (dir.path() / "folder").string() +
                ": is a folder; an output must be a regular file, a FIFO or a character device: "
                "choose another output path");

  const fs::path socket_path = dir.path() / "s.sock";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socket_path.string().size(), sizeof address.sun_path);
  std::strcpy(address.sun_path, socket_path.c_str());
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  EXPECT_NE(message_of(socket_path).find("s.sock: is a socket;"), std::string::npos);
  EXPECT_EQ(fs::status(socket_path).type(), fs::file_type::socket);
  ::close(fd);
}

// A process id that is certainly not alive: a child that has exited and been reaped.
pid_t dead_process_id() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

TEST(StaleTemporaries, NamesOfTemporaryFiles) {
  EXPECT_EQ(temporary_file_owner("nav.csv.tmp1234_0"), 1234);
  EXPECT_EQ(temporary_file_owner("a.tmp.csv.tmp77_12"), 77);
  EXPECT_EQ(temporary_file_owner(".tmp12_0"), std::nullopt);
  EXPECT_EQ(temporary_file_owner("nav.csv.tmp12_"), std::nullopt);
  EXPECT_EQ(temporary_file_owner("nav.csv.tmp_3"), std::nullopt);
  EXPECT_EQ(temporary_file_owner("nav.csv.tmp12_3x"), std::nullopt);
  EXPECT_EQ(temporary_file_owner("nav.csv"), std::nullopt);
  EXPECT_EQ(temporary_file_owner("notes.tmp"), std::nullopt);
}

TEST(StaleTemporaries, TheNextWriterRemovesThoseOfDeadProcessesOnly) {
  TempDir dir;
  const pid_t dead = dead_process_id();
  const std::string dead_name = "nav.csv.tmp" + std::to_string(dead) + "_3";
  const std::string live_name = "nav.csv.tmp" + std::to_string(::getppid()) + "_0";
  const std::string locked_name = "errors.csv.tmp" + std::to_string(dead) + "_4";
  dir.write(dead_name, "half a file");
  dir.write(live_name, "being written");
  dir.write(locked_name, "locked by a writer elsewhere");
  dir.write("notes.tmp" + std::to_string(dead), "not ours");
  fs::create_directories(dir.path() / ("folder.tmp" + std::to_string(dead) + "_1"));
  const int lock = ::open(dir.file(locked_name).c_str(), O_RDONLY);
  ASSERT_EQ(::flock(lock, LOCK_SH), 0);

  write_file_atomically(dir.path() / "metrics.json", "{}\n");

  EXPECT_FALSE(fs::exists(dir.path() / dead_name));
  EXPECT_TRUE(fs::exists(dir.path() / live_name));
  EXPECT_TRUE(fs::exists(dir.path() / locked_name));
  EXPECT_TRUE(fs::exists(dir.path() / ("notes.tmp" + std::to_string(dead))));
  EXPECT_TRUE(fs::exists(dir.path() / ("folder.tmp" + std::to_string(dead) + "_1")));
  EXPECT_EQ(contents(dir.path() / "metrics.json"), "{}\n");
  ::close(lock);
}

}  // namespace
}  // namespace stochnav

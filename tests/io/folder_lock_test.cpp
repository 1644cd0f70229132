// One writer per output folder (io/folder_lock.hpp): another process's lock refuses, a dead
// holder's does not, holders in one process nest, and the lock file goes with the last one.

#include "stochnav/io/folder_lock.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// A child process that locks `folder`, says so through a pipe and holds the lock until its
// parent closes the other pipe (or it is killed). Returns its pid once it holds the lock.
struct LockingChild {
  pid_t pid = -1;
  int release_fd = -1;
};

LockingChild lock_in_child(const fs::path& folder) {
  int locked[2];
  int release[2];
  if (::pipe(locked) != 0 || ::pipe(release) != 0) return {};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(locked[0]);
    ::close(release[1]);
    const FolderLock lock(folder);
    const char ready = 'L';
    if (::write(locked[1], &ready, 1) != 1) ::_exit(3);
    char ignored;
    while (::read(release[0], &ignored, 1) > 0) {
    }
    ::_exit(0);
  }
  ::close(locked[1]);
  ::close(release[0]);
  char ready = 0;
  const bool holds = ::read(locked[0], &ready, 1) == 1 && ready == 'L';
  ::close(locked[0]);
  return holds ? LockingChild{pid, release[1]} : LockingChild{};
}

int wait_for(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

TEST(FolderLock, AnotherProcessWritingRefusesAndItsDeathReleases) {
  const TempDir dir;
  const LockingChild child = lock_in_child(dir.path());
  ASSERT_GT(child.pid, 0);
  try {
    const FolderLock second(dir.path());
    ADD_FAILURE() << "a second writer was let in";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("another stochnav process is writing into this folder"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("choose another --out"), std::string::npos) << message;
  }
  // An output folder there is refused the same way, and leaves what was there.
  const std::string kept = dir.write("kept.csv", "an earlier result");
  EXPECT_THROW(OutputFolder{dir.path()}, InputError);
  EXPECT_TRUE(fs::exists(kept));
  // Killed while holding it (no destructor runs): the next writer gets in.
  ::kill(child.pid, SIGKILL);
  wait_for(child.pid);
  ::close(child.release_fd);
  EXPECT_NO_THROW(FolderLock{dir.path()});
}

TEST(FolderLock, HoldersInOneProcessNestAndTheLastRemovesTheFile) {
  const TempDir dir;
  const fs::path lock_file = dir.path() / FolderLock::kFileName;
  {
    const FolderLock outer(dir.path());
    EXPECT_TRUE(fs::exists(lock_file));
    {
      const FolderLock inner(dir.path() / ".");  // the same folder, spelled otherwise
      EXPECT_TRUE(fs::exists(lock_file));
    }
    EXPECT_TRUE(fs::exists(lock_file)) << "the inner holder released the outer one's lock";
    // Still locked against other processes.
    const pid_t probe = ::fork();
    if (probe == 0) {
      try {
        const FolderLock other(dir.path());
        ::_exit(0);
      } catch (const InputError&) {
        ::_exit(7);
      }
    }
    const int status = wait_for(probe);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 7) << "status " << status;
  }
  EXPECT_FALSE(fs::exists(lock_file)) << "the lock file outlived its last holder";
}

TEST(FolderLock, AFolderThatCannotBeLockedIsNamed) {
  const TempDir dir;
  try {
    const FolderLock lock(dir.path() / "missing");
    ADD_FAILURE() << "a missing folder was locked";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("missing: cannot lock the output folder"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace stochnav

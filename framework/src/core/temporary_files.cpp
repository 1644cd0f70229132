#include "stochnav/core/temporary_files.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <utility>

#include "stochnav/core/errors.hpp"

extern char** environ;  // NOLINT: POSIX declares it nowhere else

namespace stochnav {
namespace {

// The registry is a plain mutex-guarded map: the removal runs on an ordinary thread (woken
// through a pipe by the signal handler), not in the handler, so it may allocate and take locks.
struct Registry {
  std::mutex mutex;
  std::map<std::uint64_t, std::pair<std::filesystem::path, TemporaryPath::Removal>> paths;
  std::uint64_t next_id = 1;
  std::set<pid_t> children;  // started by CleanupChild, not yet reaped
};

Registry& registry() {
  static Registry* instance = new Registry();  // never destroyed: used until the last moment
  return *instance;
}

void wait_for(pid_t pid, int* status) {
  while (::waitpid(pid, status, 0) < 0 && errno == EINTR) {
  }
}

// Children first: a child still running could write into a path after its removal.
void remove_all_locked(Registry& r) {
  for (const pid_t pid : r.children) ::kill(pid, SIGKILL);
  for (const pid_t pid : r.children) wait_for(pid, nullptr);
  r.children.clear();
  std::error_code ignored;
  for (const auto& [id, entry] : r.paths) {
    if (entry.second == TemporaryPath::Removal::kWhole) {
      std::filesystem::remove_all(entry.first, ignored);
    }
  }
  for (auto it = r.paths.rbegin(); it != r.paths.rend(); ++it) {
    if (it->second.second == TemporaryPath::Removal::kIfEmpty) {
      std::filesystem::remove(it->second.first, ignored);  // fails, harmlessly, unless empty
    }
  }
  r.paths.clear();
}

int signal_pipe[2] = {-1, -1};  // the handler writes the signal number, the watcher reads it

// The whole signal handler: one async-signal-safe write. The work happens on the watcher thread.
extern "C" void forward_signal(int number) {
  const int saved_errno = errno;
  const auto byte = static_cast<unsigned char>(number);
  [[maybe_unused]] const ssize_t written = ::write(signal_pipe[1], &byte, 1);
  errno = saved_errno;
}

[[noreturn]] void watch_signals() {
  unsigned char byte = 0;
  while (::read(signal_pipe[0], &byte, 1) != 1) {
  }
  const int number = byte;
  Registry& r = registry();
  // Held until the process dies: no writer registers a new temporary file meanwhile.
  r.mutex.lock();
  remove_all_locked(r);
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  sigaction(number, &default_action, nullptr);
  sigset_t just_this;
  sigemptyset(&just_this);
  sigaddset(&just_this, number);
  pthread_sigmask(SIG_UNBLOCK, &just_this, nullptr);
  ::raise(number);
  // Not reached for the default actions of these signals.
  ::_exit(128 + number);
}

}  // namespace

TemporaryPath::TemporaryPath(std::filesystem::path path, Removal removal) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  id_ = r.next_id++;
  r.paths.emplace(id_, std::make_pair(std::move(path), removal));
}

TemporaryPath::~TemporaryPath() { release(); }

void TemporaryPath::release() {
  if (id_ == 0) return;
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  r.paths.erase(id_);
  id_ = 0;
}

void install_signal_cleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (::pipe2(signal_pipe, O_CLOEXEC) != 0) return;  // no cleanup rather than no tool
    std::thread(watch_signals).detach();
    struct sigaction action {};
    action.sa_handler = forward_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;  // interrupted reads and writes of the workers carry on
    for (const int number : {SIGINT, SIGTERM, SIGHUP}) {
      // A signal the process was started with ignored (nohup, a background job) stays ignored.
      struct sigaction current {};
      if (sigaction(number, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
      sigaction(number, &action, nullptr);
    }
  });
}

void run_before_cleanup(const std::function<void()>& action) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);  // held for good by the cleanup once it has begun
  action();
}

void create_directories_before_cleanup(const std::filesystem::path& path,
                                       std::error_code& error) {
  run_before_cleanup([&] { std::filesystem::create_directories(path, error); });
}

void create_file_before_cleanup(const std::filesystem::path& path, std::error_code& error) {
  run_before_cleanup([&] {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) {
      error.assign(errno, std::generic_category());
      return;
    }
    ::close(fd);
    error.clear();
  });
}

CleanupChild::CleanupChild(const std::vector<std::string>& argv) {
  if (argv.empty()) throw InputError("cannot start a child process: no program named");
  int pipe_fds[2] = {-1, -1};
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    throw InputError(argv[0] + ": cannot start (" + std::strerror(errno) +
                     "); too many open files?");
  }
  // dup2 onto 1 and 2 clears their close-on-exec flag; the pipe's own ends close at exec.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  std::vector<char*> arguments;
  for (const std::string& argument : argv) arguments.push_back(const_cast<char*>(argument.c_str()));
  arguments.push_back(nullptr);
  pid_t pid = -1;
  int result = 0;
  {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);  // started before the cleanup (and killed by it) or not
    result = ::posix_spawnp(&pid, arguments[0], &actions, nullptr, arguments.data(), environ);
    if (result == 0) r.children.insert(pid);
  }
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  if (result != 0) {
    ::close(pipe_fds[0]);
    throw InputError(argv[0] + ": cannot start (" + std::strerror(result) +
                     "); check that it is installed and on PATH");
  }
  pid_ = pid;
  output_fd_ = pipe_fds[0];
}

CleanupChild::~CleanupChild() {
  if (output_fd_ >= 0) ::close(output_fd_);
  if (pid_ < 0) return;
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  if (r.children.erase(pid_) == 0) return;  // killed and reaped by remove_registered_paths
  ::kill(pid_, SIGKILL);
  wait_for(pid_, nullptr);
}

int CleanupChild::wait() {
  // Wait without reaping, then reap under the lock: a pid the cleanup may still kill is never
  // one the system could have given to another process.
  siginfo_t info{};
  while (::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOWAIT) != 0 &&
         errno == EINTR) {
  }
  int status = -1;
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  if (r.children.erase(pid_) == 1) wait_for(pid_, &status);
  pid_ = -1;
  return status;
}

void remove_registered_paths() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  remove_all_locked(r);
}

}  // namespace stochnav

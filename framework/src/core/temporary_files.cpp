#include "stochnav/core/temporary_files.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

namespace stochnav {
namespace {

// The registry is a plain mutex-guarded map: the removal runs on an ordinary thread (woken
// through a pipe by the signal handler), not in the handler, so it may allocate and take locks.
struct Registry {
  std::mutex mutex;
  std::map<std::uint64_t, std::pair<std::filesystem::path, TemporaryPath::Removal>> paths;
  std::uint64_t next_id = 1;
};

Registry& registry() {
  static Registry* instance = new Registry();  // never destroyed: used until the last moment
  return *instance;
}

void remove_all_locked(Registry& r) {
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

void create_directories_before_cleanup(const std::filesystem::path& path,
                                       std::error_code& error) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);  // held for good by the cleanup once it has begun
  std::filesystem::create_directories(path, error);
}

void remove_registered_paths() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  remove_all_locked(r);
}

}  // namespace stochnav

#include "stochnav/core/temporary_files.hpp"

#include <pthread.h>
#include <unistd.h>
#include <signal.h>

#include <map>
#include <mutex>
#include <thread>
#include <utility>

namespace stochnav {
namespace {

// The registry is a plain mutex-guarded map: the removal runs on an ordinary thread (woken by
// sigwait), not in a signal handler, so it may allocate and take locks.
struct Registry {
  std::mutex mutex;
  std::map<std::uint64_t, std::filesystem::path> paths;
  std::uint64_t next_id = 1;
};

Registry& registry() {
  static Registry* instance = new Registry();  // never destroyed: used until the last moment
  return *instance;
}

void remove_all_locked(Registry& r) {
  for (const auto& [id, path] : r.paths) {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  r.paths.clear();
}

// SIGINT, SIGTERM and SIGHUP, except those the process was started with ignored (nohup, a
// background job without job control): they stay ignored.
sigset_t cleanup_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (const int number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (sigaction(number, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaddset(&set, number);
  }
  return set;
}

[[noreturn]] void watch_signals(sigset_t set) {
  int signal_number = 0;
  while (sigwait(&set, &signal_number) != 0) {
  }
  Registry& r = registry();
  // Held until the process dies: no writer registers a new temporary file meanwhile.
  r.mutex.lock();
  remove_all_locked(r);
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  sigaction(signal_number, &default_action, nullptr);
  sigset_t just_this;
  sigemptyset(&just_this);
  sigaddset(&just_this, signal_number);
  pthread_sigmask(SIG_UNBLOCK, &just_this, nullptr);
  raise(signal_number);
  // Not reached for the default actions of these signals.
  _exit(128 + signal_number);
}

}  // namespace

TemporaryPath::TemporaryPath(std::filesystem::path path) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  id_ = r.next_id++;
  r.paths.emplace(id_, std::move(path));
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
    const sigset_t set = cleanup_signals();
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread(watch_signals, set).detach();
  });
}

void remove_registered_paths() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  remove_all_locked(r);
}

}  // namespace stochnav

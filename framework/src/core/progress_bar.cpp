#include "stochnav/core/progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace stochnav {

ProgressBar::ProgressBar(std::string label, std::uint64_t total, bool enabled)
    : label_(std::move(label)),
      total_(total),
      active_(enabled),
      terminal_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() {
  if (active_ && terminal_ && !finished_) std::fputc('\n', stderr);
}

void ProgressBar::finish(std::uint64_t done) {
  if (!active_ || finished_) return;
  draw(done, true);
  finished_ = true;
}

void ProgressBar::draw(std::uint64_t done, bool last) {
  const auto now = std::chrono::steady_clock::now();
  const auto interval =
      terminal_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(30'000);
  if (!last && now - last_draw_ < interval) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (!terminal_) {
    if (last && !printed_) return;
    printed_ = true;
    if (total_ > 0) {
      const double fraction =
          std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
      const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
      std::fprintf(stderr, "%s: %.1f %%, %.0f s elapsed, ETA %.0f s%s\n", label_.c_str(),
                   100.0 * fraction, elapsed, eta, last ? " (done)" : "");
    } else {
      std::fprintf(stderr, "%s: %llu done, %.0f s elapsed%s\n", label_.c_str(),
                   static_cast<unsigned long long>(done), elapsed, last ? " (done)" : "");
    }
    std::fflush(stderr);
    return;
  }
  if (total_ > 0) {
    const double fraction = std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r%s [%s] %5.1f %%  %.0f s", label_.c_str(), bar.c_str(),
                 100.0 * fraction, elapsed);
  } else if (done > 0) {
    std::fprintf(stderr, "\r%s %llu  %.0f s", label_.c_str(),
                 static_cast<unsigned long long>(done), elapsed);
  } else {
    std::fprintf(stderr, "\r%s ...  %.0f s", label_.c_str(), elapsed);  // a stage, not counted
  }
  if (last) std::fputc('\n', stderr);
  std::fflush(stderr);
}

bool standard_error_is_terminal() { return ::isatty(STDERR_FILENO) != 0; }

ProgressTicker::ProgressTicker(std::string label, std::uint64_t total, bool enabled)
    : bar_(std::move(label), total, enabled), total_(total), enabled_(enabled) {
  if (!enabled_) return;
  thread_ = std::thread([this] {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stopping_; })) {
      bar_.show(done_.load(std::memory_order_relaxed));
    }
  });
}

ProgressTicker::~ProgressTicker() { stop(); }

void ProgressTicker::stop() {
  if (!thread_.joinable()) return;
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void ProgressTicker::finish() {
  stop();
  bar_.finish(total_ > 0 ? total_ : done_.load(std::memory_order_relaxed));
}

}  // namespace stochnav

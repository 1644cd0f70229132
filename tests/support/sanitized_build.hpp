#pragma once
// Whether the test executable is built with the address or thread sanitizer (the asan and tsan
// presets). Speed guards assert nothing there: instrumented code runs several times slower by
// design (the thread sanitizer about ten times).
//
// Statistical studies (many seeds, hours-long records) run smaller there: study_size(full,
// sanitized). Under the sanitizers a study looks for memory and undefined-behaviour errors in
// the code it runs, so that the whole suite runs under them in reasonable time (by hand: CI's
// asan stage runs the unit-level suites only, .ci/asan_stage); the floors that need the full
// size are checked only at full size (the release suite).
// STOCHNAV_STUDY_FULL_SIZE=1 runs the studies at full size in a sanitized build too
// (docs/reliability.md, "Sanitizers": the by-hand run).

#include <cstdlib>
#include <cstring>

namespace stochnav::testing {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif

/// True where a study runs at its full size and checks its statistical floors: ordinary
/// builds, and sanitized ones with STOCHNAV_STUDY_FULL_SIZE=1.
inline bool study_at_full_size() {
  const char* forced = std::getenv("STOCHNAV_STUDY_FULL_SIZE");
  return !kSanitizedBuild || (forced != nullptr && std::strcmp(forced, "1") == 0);
}

/// `full` where study_at_full_size(), else `sanitized`.
template <class T>
T study_size(T full, T sanitized) {
  return study_at_full_size() ? full : sanitized;
}

}  // namespace stochnav::testing

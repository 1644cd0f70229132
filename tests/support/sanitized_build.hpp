#pragma once
// Whether the test executable is built with the address or thread sanitizer (the asan and tsan
// presets). Speed guards assert nothing there: instrumented code runs several times slower by
// design (the thread sanitizer about ten times).

namespace stochnav::testing {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif

}  // namespace stochnav::testing

#pragma once
// STOCHNAV_WIDE_VECTOR_CLONES: a hot numeric kernel is also compiled for AVX-512 (x86-64-v4) and
// AVX2 + FMA (x86-64-v3), and the loader picks the widest the CPU has: four and two times the
// lanes of the SSE2 default, with no -march flag in the build (the binary runs anywhere).
// Apply it to plain (non-template) functions.
//
// Not under the thread sanitizer: GCC instruments the clones' IFUNC resolver too
// (__tsan_func_entry), and the dynamic loader runs that resolver while it relocates
// libstochnav.so, before libtsan is initialised: every program crashed before main. The
// default (SSE2) code is the same arithmetic, so a TSan build only loses the wider lanes.

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(__SANITIZE_THREAD__)
#define STOCHNAV_WIDE_VECTOR_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define STOCHNAV_WIDE_VECTOR_CLONES
#endif

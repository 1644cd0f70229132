#pragma once
// Large numeric buffers that fault in a few hundred huge pages rather than tens of thousands of
// small ones.

#include <cstddef>
#include <vector>

namespace stochnav {

/// An empty vector with capacity for `size` values. On Linux its memory is advised to be backed
/// by transparent huge pages before anything touches it (madvise MADV_HUGEPAGE, a hint the
/// kernel may ignore): filling a 1e7-sample record then costs a few hundred page faults instead
/// of tens of thousands, about half the time of an Allan pass. Elsewhere a plain reserve().
std::vector<double> huge_page_buffer(std::size_t size);

}  // namespace stochnav

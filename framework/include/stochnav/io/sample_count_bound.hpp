#pragma once
// An upper bound on the samples a record file holds, found without parsing it: for a streaming
// estimator that sizes its buffers by the record length (the Haar wavelet variance's delay lines)
// before reading.

#include <cstddef>
#include <optional>

#include "stochnav/io/record.hpp"

namespace stochnav {

/// Raw .f64 / .f32 files: the exact count (bytes / width / channels). Plain text and CSV: the
/// number of lines (one sample per line at most), counted in one pass of 1 MB reads. Gzip
/// files: nullopt (the count needs the whole decompression). Throws InputError when the file
/// cannot be opened.
std::optional<std::size_t> sample_count_bound(const ReadOptions& options);

}  // namespace stochnav

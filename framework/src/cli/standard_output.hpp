#pragma once
// Standard output as a checked output: every write, and the final flush and close, either
// succeeds or throws InputError (exit code 2), as coreutils' close_stdout does. A full disk, a
// full device (/dev/full) or a closed standard output is an error, never a silent exit 0.

#include <string_view>

namespace stochnav::cli {

/// Opens /dev/null read-only on any of the descriptors 0, 1 and 2 the process was started
/// without (`stochnav ... >&-`). Call it first in main(). Without it the first file the command
/// opens would take descriptor 1, and text meant for standard output would go into that file;
/// with it, writes to a closed standard output fail (EBADF) and are reported.
void reserve_standard_streams();

/// Writes `text` to standard output and flushes it (and whatever std::cout or stdout held
/// before). Throws InputError "standard output: cannot write (REASON); ..." on any failure.
void write_standard_output(std::string_view text);

/// Flushes std::cout and stdout and closes descriptor 1; throws InputError as write_standard_output
/// if any earlier write to them failed or the flush or close fails. Call it once, when the
/// command has finished; nothing may be written to standard output afterwards.
void close_standard_output();

}  // namespace stochnav::cli

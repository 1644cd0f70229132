#pragma once
// What an output path names, and so how it is written (docs/reliability.md, "Where outputs go").

#include <filesystem>

namespace stochnav {

/// Where an output named by the user goes.
///  - A path that does not exist, or a regular file: replaced atomically (PendingFile: a
///    temporary file beside it, renamed over it when complete).
///  - A symbolic link (or a chain of them): followed; the rules apply to its final target, so a
///    link to a regular file stays a link and its target is replaced atomically, and a dangling
///    link gets its target created.
///  - A FIFO or a character device (/dev/null, a terminal, /dev/stdout on a pipe): written in
///    place, opened for writing and streamed, never renamed over nor removed. Opening a FIFO
///    waits for its reader, as the shell's `>` does; a failure part-way leaves what its reader
///    has already seen.
///  - A folder, a socket or a block device: refused (InputError naming the path, exit code 2).
struct OutputTarget {
  std::filesystem::path path;  ///< the file written: the link's final target for a link
  bool in_place = false;       ///< true: stream into `path` itself (FIFO, character device)
};

/// The target of an output named `path` (rules above). Throws InputError "PATH: ..." for a
/// folder, a socket, a block device, or more than 40 links in a chain.
OutputTarget resolve_output_target(const std::filesystem::path& path);

}  // namespace stochnav

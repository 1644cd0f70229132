#pragma once
// Messages as one printable line: what a file or an option contained is echoed in them.

#include <string>
#include <string_view>

namespace stochnav::cli {

/// `message` with control characters (bytes below 0x20, and 0x7f) written as escapes: "\n",
/// "\r", "\t", "\x1b", ... so an echoed cell cannot break the one-line message or drive the
/// terminal. Other bytes (UTF-8 text) are kept.
std::string printable(std::string_view message);

}  // namespace stochnav::cli

#pragma once
// Reading a JSON document (a configuration or a noise model) from a file.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace stochnav {

/// Parses the JSON file at `path`. Throws InputError, one line naming the file, for everything a
/// user can get wrong: a missing or unreadable file, a folder, invalid syntax (with the parser's
/// position), a number beyond the range of a double (1e400), a key twice in one object ("PATH:
/// duplicate key at /noise/gyro/plugin; ...": JSON leaves it undefined which one counts, so
/// neither is taken). `what` says what the file should be ("the run config", "--model"), for the
/// hint. Never throws nlohmann's own exceptions.
nlohmann::json read_json_document(const std::filesystem::path& path, std::string_view what);

/// The same for JSON text that did not come from a file (an option's value): `name` stands for
/// the file name in the messages ("--params").
nlohmann::json parse_json_document(const std::string& text, const std::string& name);

}  // namespace stochnav

#pragma once
// Reading a JSON document from a file, with errors that name the file.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>

namespace stochnav {

/// Parses the JSON file. Throws InputError "<file>: <problem>; <fix>" when it is missing or
/// unreadable, a folder, or not valid JSON (with the parser's position). `what` names the
/// document in messages ("scenario config").
nlohmann::json read_json_file(const std::filesystem::path& file, std::string_view what);

}  // namespace stochnav

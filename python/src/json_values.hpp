#pragma once
// JSON between Python and the library: configs given as dicts or as file paths, and results
// (metrics, reports) handed back as dicts. The conversion goes through Python's json module, so a
// dict holds exactly what a config file would (numpy scalars and arrays are written as numbers
// and lists).

#include "pybind.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace stochnav::python {

/// A dict (or list, number, ...) as JSON. Throws ConfigError naming `what` when it cannot be
/// written as JSON (a set, an object).
nlohmann::json json_from_python(const py::handle& object, const std::string& what);

/// JSON as Python objects (dict, list, float, int, str, bool, None).
py::object python_from_json(const nlohmann::json& value);

/// True for a str or an os.PathLike: the argument names a file.
bool is_path(const py::handle& object);

/// The path a str or os.PathLike names.
std::filesystem::path path_from_python(const py::handle& object);

/// A config given as a dict or as a path to its JSON file.
struct JsonDocument {
  nlohmann::json json;
  /// Relative paths inside start here: the file's folder, or the working folder for a dict.
  std::filesystem::path folder;
  /// The file (absolute), or "<folder>/<what> (dict)" standing for it in messages.
  std::filesystem::path file;
  bool from_file = false;
};

/// Reads the file a path names (read_json_document: InputError naming file and line) or takes
/// the dict. `what` says what it should be ("the run config"). Anything else: ValueError.
JsonDocument json_document(const py::handle& object, const std::string& what);

}  // namespace stochnav::python

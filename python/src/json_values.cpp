#include "json_values.hpp"

#include "stochnav/core/errors.hpp"
#include "stochnav/io/json_document.hpp"

namespace stochnav::python {

nlohmann::json json_from_python(const py::handle& object, const std::string& what) {
  const py::module_ json = py::module_::import("json");
  // numpy values: their Python equivalents (np.int64 is no int to json).
  const py::cpp_function plain([](const py::handle& value) -> py::object {
    if (py::hasattr(value, "tolist")) return value.attr("tolist")();
    throw py::type_error("not JSON");
  });
  std::string text;
  try {
    text = py::str(json.attr("dumps")(object, py::arg("default") = plain, py::arg("allow_nan") = false));
  } catch (const py::error_already_set& error) {
    throw ConfigError(what + ": cannot be written as JSON (" + std::string(py::str(error.value())) +
                      "); use dicts, lists, strings, finite numbers, booleans and None");
  }
  return parse_json_document(text, what);
}

py::object python_from_json(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

bool is_path(const py::handle& object) {
  return py::isinstance<py::str>(object) ||
         py::isinstance(object, py::module_::import("os").attr("PathLike"));
}

std::filesystem::path path_from_python(const py::handle& object) {
  return std::filesystem::path(
      py::str(py::module_::import("os").attr("fspath")(object)).cast<std::string>());
}

JsonDocument json_document(const py::handle& object, const std::string& what) {
  JsonDocument document;
  if (is_path(object)) {
    document.file = std::filesystem::absolute(path_from_python(object));
    document.folder = document.file.parent_path();
    document.json = read_json_document(document.file, what);
    document.from_file = true;
    return document;
  }
  if (!py::isinstance<py::dict>(object)) {
    throw py::value_error(what + ": expected a dict or the path of a JSON file, got " +
                          std::string(py::str(py::type::of(object).attr("__name__"))));
  }
  document.folder = std::filesystem::current_path();
  document.file = document.folder / (what + " (dict)");
  document.json = json_from_python(object, what);
  return document;
}

}  // namespace stochnav::python

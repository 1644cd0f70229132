// stochnav's input errors as Python exceptions: InputError and ConfigError keep their names and
// their one-line messages (what, where, how to fix it) and derive from ValueError, so
// `except ValueError` catches every bad input. Anything else the library throws is an internal
// failure (RuntimeError, pybind11's default).

#include "bindings.hpp"
#include "stochnav/core/errors.hpp"

namespace stochnav::python {

void bind_errors(py::module_& module) {
  // The translators catch by reference: MissingDataError, a ConfigError, arrives as one.
  auto& config_error = py::register_exception<ConfigError>(module, "ConfigError", PyExc_ValueError);
  auto& input_error = py::register_exception<InputError>(module, "InputError", PyExc_ValueError);
  config_error.attr("__doc__") =
      "Bad configuration (a config dict or file, an argument): the message names the JSON "
      "pointer or the argument, the value found and the expected form. A ValueError.";
  input_error.attr("__doc__") =
      "Bad input data (a record, an array): the message names the file and line or the array "
      "index, what is wrong and how to fix it. A ValueError.";
}

}  // namespace stochnav::python

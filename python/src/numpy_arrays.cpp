#include "numpy_arrays.hpp"

#include <cmath>
#include <string_view>

#include "stochnav/core/errors.hpp"

namespace stochnav::python {
namespace {

// numpy's kind characters of real (or boolean) arrays: the ones float64 represents.
bool is_real_kind(char kind) { return kind == 'f' || kind == 'i' || kind == 'u' || kind == 'b'; }

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t axis = 0; axis < array.ndim(); ++axis) {
    text += std::to_string(array.shape(axis)) + (array.ndim() == 1 ? "," : "");
    if (axis + 1 < array.ndim()) text += ", ";
  }
  return text + ")";
}

// The object as a numpy array of any dtype (a list becomes one), or ValueError.
py::array as_array(const py::handle& object, const std::string& name) {
  py::array array;
  try {
    array = py::module_::import("numpy").attr("asarray")(object);
  } catch (const py::error_already_set&) {
    throw py::value_error(name + ": not an array of numbers; pass a 1-D numpy array of floats");
  }
  const char kind = array.dtype().kind();
  if (!is_real_kind(kind)) {
    throw py::value_error(name + ": dtype " + std::string(py::str(array.dtype())) +
                          " is not real numbers; pass a 1-D array of floats (complex, object, "
                          "string and date arrays are refused)");
  }
  return array;
}

}  // namespace

SampleArray::SampleArray(const py::handle& object, std::string name) : name_(std::move(name)) {
  const py::array array = as_array(object, name_);
  if (array.ndim() != 1) {
    throw py::value_error(name_ + ": shape " + shape_text(array) +
                          " is not 1-D; pass one channel (e.g. data[:, k]) or x.ravel()");
  }
  // The array itself when it is contiguous float64, else one converted copy.
  array_ = py::array_t<double, py::array::c_style>::ensure(array);
  if (!array_) throw py::error_already_set();
  values_ = std::span<const double>(array_.data(), static_cast<std::size_t>(array_.size()));
}

void SampleArray::check_finite(std::size_t minimum) const {
  if (values_.size() < minimum) {
    throw InputError(name_ + ": " + std::to_string(values_.size()) + " sample(s); at least " +
                     std::to_string(minimum) + " are needed");
  }
  for (std::size_t i = 0; i < values_.size(); ++i) {
    if (!std::isfinite(values_[i])) {
      throw InputError(name_ + "[" + std::to_string(i) + "] is " +
                       (std::isnan(values_[i]) ? "nan" : "infinite") +
                       "; stochnav needs finite samples: cut the record at the gap, or fill it");
    }
  }
}

RealArgument real_argument(const py::handle& object, const std::string& name) {
  const py::array array = as_array(object, name);
  if (array.ndim() > 1) {
    throw py::value_error(name + ": shape " + shape_text(array) + " is not a number or 1-D");
  }
  const auto converted = py::array_t<double, py::array::c_style>::ensure(array);
  if (!converted) throw py::error_already_set();
  RealArgument argument;
  argument.scalar = array.ndim() == 0;
  argument.values.assign(converted.data(), converted.data() + converted.size());
  return argument;
}

py::object real_result(std::vector<double>&& values, bool scalar) {
  if (scalar) return py::float_(values.at(0));
  return to_numpy(std::move(values));
}

}  // namespace stochnav::python

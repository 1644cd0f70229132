#pragma once
// numpy arrays in and out of the stochnav module.
//
// In: any 1-D sequence of real numbers. A C-contiguous float64 array is used where it is, with no
// copy; anything else (other real dtypes, a strided view, a list) is converted once to a
// contiguous float64 copy, as np.ascontiguousarray(x, dtype=np.float64) would. Complex, object,
// string and date arrays, and arrays that are not 1-D, raise ValueError naming the argument.
// Samples must be finite (ValueError naming the first index that is not).
// Out: std::vector results handed to numpy without a copy (the array owns the vector).

#include "pybind.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace stochnav::python {

/// A 1-D float64 view of a Python object, kept alive as long as this object.
class SampleArray final {
 public:
  /// `name` is the argument's name in messages ("x"). Needs the GIL.
  SampleArray(const py::handle& object, std::string name);

  std::span<const double> values() const { return values_; }
  const std::string& name() const { return name_; }
  /// Throws InputError "<name>[i] is nan; ..." at the first NaN or infinite sample, and when
  /// there are fewer than `minimum` samples. Safe without the GIL.
  void check_finite(std::size_t minimum = 2) const;

 private:
  py::array_t<double, py::array::c_style> array_;
  std::span<const double> values_;
  std::string name_;
};

/// A numpy array that owns `values` (moved, not copied).
template <typename T>
py::array_t<T> to_numpy(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* pointer) { delete static_cast<std::vector<T>*>(pointer); });
  return py::array_t<T>(static_cast<py::ssize_t>(owned->size()), owned->data(), owner);
}

/// A float64 array of the elements of `values` converted by `field` (one copy: the result
/// tables are small).
template <typename Row, typename Field>
py::array_t<double> column_of(const std::vector<Row>& rows, Field field) {
  std::vector<double> column;
  column.reserve(rows.size());
  for (const Row& row : rows) column.push_back(static_cast<double>(field(row)));
  return to_numpy(std::move(column));
}

/// The same as an int64 array.
template <typename Row, typename Field>
py::array_t<std::int64_t> integer_column_of(const std::vector<Row>& rows, Field field) {
  std::vector<std::int64_t> column;
  column.reserve(rows.size());
  for (const Row& row : rows) column.push_back(static_cast<std::int64_t>(field(row)));
  return to_numpy(std::move(column));
}

/// tau (or any real argument) given as a number or a 1-D array: its values as a vector, and
/// whether it was a scalar (the result is then returned as a float).
struct RealArgument {
  std::vector<double> values;
  bool scalar = false;
};
RealArgument real_argument(const py::handle& object, const std::string& name);

/// A result for a RealArgument: a float for a scalar, else a numpy array.
py::object real_result(std::vector<double>&& values, bool scalar);

}  // namespace stochnav::python

#pragma once
// The pybind11 headers every file of the module includes, all of them in every file: a type
// whose caster one translation unit sees (std::vector through stl.h) and another does not would
// be converted differently in each (an ODR violation pybind11's documentation warns of).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace stochnav::python {
namespace py = pybind11;
}  // namespace stochnav::python

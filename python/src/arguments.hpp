#pragma once
// Arguments the module's functions share, checked with messages that name them as Python
// spells them (ConfigError, a ValueError).

#include "pybind.hpp"

#include <cstdint>
#include <string>

#include "stochnav/core/units.hpp"
#include "stochnav/io/record.hpp"

namespace stochnav::python {

/// "rate" or "phase" (the `data` argument).
DataKind data_kind_argument(const std::string& data);

/// The sampling rate `rate` (Hz): finite, within [kMinRecordRateHz, kMaxRecordRateHz].
double rate_argument(double rate_hz);

/// A random seed: a Python int in [0, 2^64 - 1] (a negative one is refused, not wrapped).
std::uint64_t seed_argument(const py::handle& seed, const std::string& name);

/// `unit`: "deg/h", "deg/s", "rad/s", "m/s^2", "g" or "plain" (core/units.hpp).
Unit unit_argument(const std::string& unit);

}  // namespace stochnav::python

#include "arguments.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "stochnav/core/errors.hpp"

namespace stochnav::python {

DataKind data_kind_argument(const std::string& data) {
  if (data == "rate") return DataKind::kRate;
  if (data == "phase") return DataKind::kPhase;
  throw ConfigError("data '" + data + "': use \"rate\" (a rate: gyro rate, fractional frequency) "
                    "or \"phase\" (its integral: angle, clock phase)");
}

double rate_argument(double rate_hz) {
  if (!(rate_hz >= kMinRecordRateHz && rate_hz <= kMaxRecordRateHz)) {
    throw ConfigError(fmt::format("rate {:g} Hz: give the sampling rate in Hz, from {:g} to {:g}",
                                  rate_hz, kMinRecordRateHz, kMaxRecordRateHz));
  }
  return rate_hz;
}

std::uint64_t seed_argument(const py::handle& seed, const std::string& name) {
  if (!py::isinstance<py::int_>(seed) || py::isinstance<py::bool_>(seed) ||
      seed < py::int_(0) ||
      seed > py::int_(std::numeric_limits<std::uint64_t>::max())) {
    throw ConfigError(name + " " + std::string(py::repr(seed)) +
                      ": give a whole number from 0 to 2^64 - 1");
  }
  return seed.cast<std::uint64_t>();
}

Unit unit_argument(const std::string& unit) {
  try {
    return parse_unit(unit);
  } catch (const ConfigError& error) {
    throw ConfigError(std::string("unit: ") + error.what());
  }
}

}  // namespace stochnav::python

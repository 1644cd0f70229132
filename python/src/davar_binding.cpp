// stochnav.davar: the dynamic Allan deviation of a numpy record, window by window; the library
// call of `stochnav davar` (cli/davar_command.cpp) on an array.

#include <fmt/format.h>

#include <cstring>

#include "arguments.hpp"
#include "bindings.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/stats/davar.hpp"

namespace stochnav::python {
namespace {

struct DavarTable {
  double rate_hz = 0.0;
  bool causal = false;
  std::size_t window = 0;
  std::size_t step = 0;
  py::array_t<double> t, tau, dev;
  py::array_t<std::int64_t> m, n;
};

/// A whole number of samples >= 1 from a Python int (a negative one is refused, not wrapped).
std::size_t sample_count_argument(long long value, const char* name) {
  if (value < 1) {
    throw ConfigError(fmt::format("{} {}: give a whole number of samples >= 1", name, value));
  }
  return static_cast<std::size_t>(value);
}

DavarTable davar(const py::object& x, double rate, long long window, long long step,
                 bool causal, const std::string& data) {
  DavarTable table;
  table.rate_hz = rate_argument(rate);
  table.causal = causal;
  const DataKind kind = data_kind_argument(data);
  const DavarOptions options{.window = sample_count_argument(window, "window"),
                             .step = sample_count_argument(step, "step"),
                             .causal = causal,
                             .m_values = {}};
  table.window = options.window;
  table.step = options.step;
  const SampleArray samples(x, "x");
  DavarResult result;
  {
    py::gil_scoped_release release;
    samples.check_finite();
    result = dynamic_allan_deviation(samples.values(), kind, table.rate_hz, 0.0, options, "x");
  }
  table.t = to_numpy(std::move(result.time_s));
  table.tau = to_numpy(std::move(result.tau_s));
  std::vector<std::int64_t> m(result.m.begin(), result.m.end());
  std::vector<std::int64_t> n(result.terms.begin(), result.terms.end());
  table.m = to_numpy(std::move(m));
  table.n = to_numpy(std::move(n));
  const std::size_t taus = result.m.size();
  table.dev = py::array_t<double>({static_cast<py::ssize_t>(result.adev.size()),
                                   static_cast<py::ssize_t>(taus)});
  double* out = table.dev.mutable_data();
  for (std::size_t k = 0; k < result.adev.size(); ++k) {
    std::memcpy(out + k * taus, result.adev[k].data(), taus * sizeof(double));
  }
  return table;
}

constexpr const char* kDavarDoc = R"(Dynamic Allan deviation (DAVAR): the overlapping Allan deviation of every window.

The library call of `stochnav davar` on an array: window k covers samples
[k * step, k * step + window); its deviations at the window's octave taus equal the OADEV of
that window alone (Zhang et al. 2017, Eq. 3-5).

Parameters
----------
x, rate : 1-D array of float, float
    As for allan: rate samples (unit U) or, data="phase", their integral (U*s); the sampling
    rate in Hz.
window : int
    Samples per window (>= 4, at most len(x)).
step : int
    Samples between window starts (>= 1).
causal : bool
    Time each window at its end (computable as soon as its last sample arrives) instead of
    its centre.
data : str
    "rate" or "phase".

Returns
-------
DavarResult
    t (s, analysis time of each window, from the first sample at t = 0), tau (s), m, n (terms
    per window at each tau), and dev, shape (len(t), len(tau)), in U.
)";

}  // namespace

void bind_davar(py::module_& module) {
  py::class_<DavarTable>(module, "DavarResult",
                         "Result of stochnav.davar: t (s), tau (s), m, n and dev[window, tau].")
      .def_readonly("t", &DavarTable::t, "analysis time of each window (s)")
      .def_readonly("tau", &DavarTable::tau, "averaging times (s)")
      .def_readonly("m", &DavarTable::m, "averaging factors")
      .def_readonly("n", &DavarTable::n, "terms per window at each tau")
      .def_readonly("dev", &DavarTable::dev, "overlapping Allan deviation [window, tau]")
      .def_readonly("rate_hz", &DavarTable::rate_hz, "sampling rate (Hz)")
      .def_readonly("window", &DavarTable::window, "samples per window")
      .def_readonly("step", &DavarTable::step, "samples between window starts")
      .def_readonly("causal", &DavarTable::causal, "windows timed at their end")
      .def("__repr__", [](const DavarTable& t) {
        return fmt::format("<DavarResult: {} windows of {} samples every {} ({}), {} taus from "
                           "{:g} to {:g} s>",
                           t.t.size(), t.window, t.step, t.causal ? "causal" : "centred",
                           t.tau.size(), t.tau.size() ? t.tau.at(0) : 0.0,
                           t.tau.size() ? t.tau.at(t.tau.size() - 1) : 0.0);
      });
  module.def("davar", &davar, py::arg("x"), py::arg("rate"), py::arg("window"), py::arg("step"),
             py::arg("causal") = false, py::arg("data") = "rate", kDavarDoc);
}

}  // namespace stochnav::python

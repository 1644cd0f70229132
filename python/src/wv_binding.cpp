// stochnav.wv: the Haar wavelet variance of a numpy record with the R package wv's 95 %
// intervals, classical or robust; the library calls of `stochnav wv` (cli/wv_command.cpp).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "arguments.hpp"
#include "bindings.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/stats/robust_wavelet_variance.hpp"
#include "stochnav/stats/wavelet_variance.hpp"

namespace stochnav::python {
namespace {

struct WvTable {
  bool robust = false;
  double efficiency = 0.0;
  double rate_hz = 0.0;
  std::size_t samples = 0;  ///< rate samples the variance was computed from
  std::vector<WaveletVariancePoint> points;
  py::array_t<std::int64_t> level, scale, n;
  py::array_t<double> scale_s, wv, lo, hi;
};

/// Rate samples of the record: x itself, or the phase differences times the rate.
std::vector<double> rate_differences(std::span<const double> phase, double rate_hz) {
  std::vector<double> rate(phase.size() > 0 ? phase.size() - 1 : 0);
  for (std::size_t i = 0; i < rate.size(); ++i) rate[i] = (phase[i + 1] - phase[i]) * rate_hz;
  return rate;
}

std::vector<WaveletVariancePoint> wavelet_variance_of(std::span<const double> rate,
                                                      double rate_hz, bool robust,
                                                      double efficiency) {
  if (wavelet_variance_levels(rate.size()) < 3) {
    throw InputError(fmt::format("x: {} rate samples give {} wavelet-variance scale(s); wv needs "
                                 "at least 3 (16 samples or more); use a longer record",
                                 rate.size(), std::max(wavelet_variance_levels(rate.size()), 0)));
  }
  if (std::all_of(rate.begin(), rate.end(), [&](double y) { return y == rate.front(); })) {
    throw InputError("x: the rate is constant (every sample the same), so its wavelet variance "
                     "is zero at every scale; check the array (and data: rate or phase)");
  }
  if (!robust) return haar_wavelet_variance(rate, rate_hz);
  auto points = robust_haar_wavelet_variance(rate, rate_hz, efficiency);
  for (const auto& p : points) {
    if (!std::isfinite(p.variance)) {
      throw InputError(fmt::format(
          "x: the wavelet coefficients at scale {} samples are all equal (a straight-line "
          "record?), so their robust scale is undefined; use robust=False",
          p.scale_samples));
    }
  }
  return points;
}

WvTable wv(const py::object& x, double rate, bool robust, double efficiency,
           const std::string& data) {
  WvTable table;
  table.rate_hz = rate_argument(rate);
  table.robust = robust;
  table.efficiency = efficiency;
  const DataKind kind = data_kind_argument(data);
  if (robust && !(efficiency >= 0.01 && efficiency <= 0.99)) {
    throw ConfigError(fmt::format("efficiency {:g}: give the robust estimate's efficiency at the "
                                  "Gaussian in [0.01, 0.99] (default 0.6)",
                                  efficiency));
  }
  const SampleArray samples(x, "x");
  {
    py::gil_scoped_release release;
    samples.check_finite();
    if (kind == DataKind::kPhase) {
      const auto rate_samples = rate_differences(samples.values(), table.rate_hz);
      table.samples = rate_samples.size();
      table.points = wavelet_variance_of(rate_samples, table.rate_hz, robust, efficiency);
    } else {
      table.samples = samples.values().size();
      table.points = wavelet_variance_of(samples.values(), table.rate_hz, robust, efficiency);
    }
  }
  const auto& points = table.points;
  table.level = integer_column_of(points, [](const WaveletVariancePoint& p) { return p.level; });
  table.scale = integer_column_of(points, [](const auto& p) { return p.scale_samples; });
  table.n = integer_column_of(points, [](const WaveletVariancePoint& p) { return p.coefficients; });
  table.scale_s = column_of(points, [](const WaveletVariancePoint& p) { return p.scale_s; });
  table.wv = column_of(points, [](const WaveletVariancePoint& p) { return p.variance; });
  table.lo = column_of(points, [](const WaveletVariancePoint& p) { return p.lower; });
  table.hi = column_of(points, [](const WaveletVariancePoint& p) { return p.upper; });
  return table;
}

std::string wv_repr(const WvTable& table) {
  std::string text = fmt::format(
      "<WvResult: Haar wavelet variance ({}) of {} rate samples at {:g} Hz, {} scales, 95 % "
      "interval>\n",
      table.robust ? fmt::format("robust, efficiency {:g}", table.efficiency) : "classical",
      table.samples, table.rate_hz, table.points.size());
  text += fmt::format("{:>5} {:>9} {:>12} {:>9} {:>12} {:>12} {:>12}\n", "level", "scale",
                      "scale_s", "n", "lo", "wv", "hi");
  for (const auto& p : table.points) {
    text += fmt::format("{:>5} {:>9} {:>12.5e} {:>9} {:>12.5e} {:>12.5e} {:>12.5e}\n", p.level,
                        p.scale_samples, p.scale_s, p.coefficients, p.lower, p.variance, p.upper);
  }
  text.pop_back();
  return text;
}

constexpr const char* kWvDoc = R"(Haar wavelet variance at dyadic scales with the R package wv's 95 % interval.

The library calls of `stochnav wv` on an array: levels j = 1 .. floor(log2 N) - 1, scale 2^j
samples; in expectation half the Allan variance at half the scale.

Parameters
----------
x, rate : 1-D array of float, float
    As for allan: rate samples (unit U) or, data="phase", their integral (U*s); the sampling
    rate in Hz.
robust : bool
    Tukey-biweight M-estimate of each level's scale, as wv(robust = TRUE); resists outliers.
efficiency : float
    The robust estimate's efficiency at the Gaussian, in [0.01, 0.99] (wv's default 0.6).
data : str
    "rate" or "phase".

Returns
-------
WvResult
    Arrays per level: level, scale (samples), scale_s (s), n (coefficients), wv (U^2), lo and
    hi (the 95 % interval, U^2).
)";

}  // namespace

void bind_wv(py::module_& module) {
  py::class_<WvTable>(module, "WvResult",
                      "Result of stochnav.wv: arrays level, scale, scale_s (s), n, wv, lo, hi "
                      "(95 % interval), in the unit of the rate squared.")
      .def_readonly("robust", &WvTable::robust)
      .def_readonly("efficiency", &WvTable::efficiency)
      .def_readonly("rate_hz", &WvTable::rate_hz, "sampling rate (Hz)")
      .def_readonly("samples", &WvTable::samples, "rate samples used")
      .def_readonly("level", &WvTable::level, "level j >= 1")
      .def_readonly("scale", &WvTable::scale, "scale 2^j (samples)")
      .def_readonly("scale_s", &WvTable::scale_s, "scale 2^j / rate (s)")
      .def_readonly("n", &WvTable::n, "wavelet coefficients at the level")
      .def_readonly("wv", &WvTable::wv, "wavelet variance (U^2)")
      .def_readonly("lo", &WvTable::lo, "lower bound of the 95 % interval (U^2)")
      .def_readonly("hi", &WvTable::hi, "upper bound of the 95 % interval (U^2)")
      .def("__len__", [](const WvTable& t) { return t.points.size(); })
      .def("__repr__", &wv_repr);
  module.def("wv", &wv, py::arg("x"), py::arg("rate"), py::arg("robust") = false,
             py::arg("efficiency") = kWvRobustEfficiency, py::arg("data") = "rate", kWvDoc);
}

}  // namespace stochnav::python

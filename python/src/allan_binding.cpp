// stochnav.allan: the Allan-family deviations of a numpy record with Stable32's confidence
// intervals; the library calls of `stochnav allan` (cli/allan_command.cpp) on an array.

#include <fmt/format.h>

#include <memory>

#include "arguments.hpp"
#include "bindings.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"
#include "stochnav/stats/tau_spacing_names.hpp"

namespace stochnav::python {
namespace {

/// The result of stochnav.allan: one row per averaging time, as `stochnav allan --format json`.
struct AllanResult {
  std::string deviation;
  std::string data;
  double rate_hz = 0.0;
  std::size_t samples = 0;
  std::vector<DeviationPoint> points;
  py::array_t<std::int64_t> m, n, alpha;
  py::array_t<double> tau, dev, lo, hi, edf;
};

/// The phase of the samples: a new array for rate data (integrated as the CLI integrates a
/// record it reads), the samples themselves for phase data.
class PhaseOfSamples final {
 public:
  PhaseOfSamples(std::span<const double> samples, DataKind kind, double tau0_s) {
    if (kind == DataKind::kPhase) {
      phase_ = samples;
      return;
    }
    integrated_ = phase_array_from_rate(samples, tau0_s);
    if (!integrated_) {
      throw InputError("x: the samples do not sum to a finite number (values near 1e308); "
                       "rescale the record");
    }
    phase_ = std::span<const double>(integrated_.get(), samples.size() + 1);
  }
  std::span<const double> phase() const { return phase_; }

 private:
  std::shared_ptr<double[]> integrated_;
  std::span<const double> phase_;
};

AllanResult allan(const py::object& x, double rate, const std::string& deviation,
                  const std::string& taus, const std::string& data, const std::string& edf) {
  AllanResult result;
  const Deviation kind = parse_deviation(deviation);
  const EdfRule edf_rule = parse_edf_rule(edf);
  const TauSpacing spacing = parse_tau_spacing(taus, "taus");
  const DataKind data_kind = data_kind_argument(data);
  result.rate_hz = rate_argument(rate);
  result.deviation = std::string(deviation_name(kind));
  result.data = data;
  const SampleArray samples(x, "x");
  result.samples = samples.values().size();
  {
    py::gil_scoped_release release;
    samples.check_finite();
    const double tau0_s = 1.0 / result.rate_hz;
    const PhaseOfSamples phase(samples.values(), data_kind, tau0_s);
    const auto m_values = averaging_factors(kind, spacing, phase.phase().size(), tau0_s);
    if (m_values.empty()) {
      throw InputError(fmt::format("x: {} samples are too few for any {} averaging time; use a "
                                   "longer record",
                                   result.samples, result.deviation));
    }
    result.points =
        compute_deviation(kind, phase.phase(), tau0_s, m_values, kStable32Confidence, edf_rule);
  }
  const auto& points = result.points;
  result.m = integer_column_of(points, [](const DeviationPoint& p) { return p.m; });
  result.n = integer_column_of(points, [](const DeviationPoint& p) { return p.terms; });
  result.alpha = integer_column_of(points, [](const DeviationPoint& p) { return p.alpha; });
  result.tau = column_of(points, [](const DeviationPoint& p) { return p.tau_s; });
  result.dev = column_of(points, [](const DeviationPoint& p) { return p.deviation; });
  result.lo = column_of(points, [](const DeviationPoint& p) { return p.lower; });
  result.hi = column_of(points, [](const DeviationPoint& p) { return p.upper; });
  result.edf = column_of(points, [](const DeviationPoint& p) { return p.edf; });
  return result;
}

std::string allan_repr(const AllanResult& result) {
  std::string text = fmt::format("<AllanResult: {} of {} {} samples at {:g} Hz, {} taus>\n",
                                 result.deviation, result.samples, result.data, result.rate_hz,
                                 result.points.size());
  text += fmt::format("{:>9} {:>12} {:>9} {:>5} {:>10} {:>12} {:>12} {:>12}\n", "m", "tau", "n",
                      "alpha", "edf", "lo", "dev", "hi");
  for (const auto& p : result.points) {
    text += fmt::format("{:>9} {:>12.5e} {:>9} {:>5} {:>10.4g} {:>12.5e} {:>12.5e} {:>12.5e}\n",
                        p.m, p.tau_s, p.terms, p.alpha, p.edf, p.lower, p.deviation, p.upper);
  }
  text.pop_back();
  return text;
}

constexpr const char* kAllanDoc = R"(Allan-family deviation with Stable32's 68.3 % confidence intervals.

The library call of `stochnav allan` on an array (no file): same numbers, same checks.

Parameters
----------
x : 1-D array of float
    The record. data="rate": rate samples in any unit U (deg/h, rad/s, fractional frequency);
    data="phase": their integral (U*s: angle, clock phase in s). A C-contiguous float64 array
    is read in place; other real dtypes or strided views are converted to a float64 copy.
rate : float
    Sampling rate in Hz (tau0 = 1 / rate s).
deviation : str
    "oadev" (overlapping Allan), "adev", "mdev" (modified), "tdev" (time deviation, in U*s),
    "hdev", "ohdev" (Hadamard), "totdev" (total), "mtotdev", "ttotdev" (modified and time
    total, ttotdev in U*s), "htotdev" (Hadamard total, Stable32's bias correction),
    "htotdev_nobias", "theo1" (tau = 0.75 m / rate, ThêoBR bias removal), "theo1_nobias",
    "mtie", "tierms" (time interval errors, U*s; no interval: lo, hi, edf NaN).
taus : str
    Averaging factors m (tau = m / rate): "octave" (1, 2, 4, ...), "decade" (1, 2, 4, 10, ...),
    "dense" (about 10 per decade) or "all" (Stable32's "all tau").
data : str
    "rate" or "phase" (see x).
edf : str
    "plausible" (default): the smallest EDF over the noise types the identification leaves
    open at each tau (docs/allan.md); "stable32": the identified type's, as Stable32.

Returns
-------
AllanResult
    Arrays, one entry per tau: tau (s), dev (U; U*s for tdev), lo and hi (the 68.3 %
    interval, U), n (terms of the estimator), edf (equivalent degrees of freedom), alpha
    (identified power-law noise, S_y(f) ~ f^alpha), m (averaging factor).

Raises
------
InputError (a ValueError)
    NaN or infinite samples, a record too short for any tau.
ConfigError (a ValueError)
    An unknown deviation, taus, data or edf, a rate outside 1e-9 .. 1e9 Hz.
)";

}  // namespace

void bind_allan(py::module_& module) {
  py::class_<AllanResult>(module, "AllanResult",
                          "Result of stochnav.allan: arrays tau (s), dev, lo, hi (68.3 % "
                          "interval), n, edf, alpha, m; len() is the number of taus.")
      .def_readonly("deviation", &AllanResult::deviation, "estimator name, e.g. \"oadev\"")
      .def_readonly("data", &AllanResult::data, "\"rate\" or \"phase\"")
      .def_readonly("rate_hz", &AllanResult::rate_hz, "sampling rate (Hz)")
      .def_readonly("samples", &AllanResult::samples, "samples of x")
      .def_readonly("tau", &AllanResult::tau, "averaging time (s)")
      .def_readonly("dev", &AllanResult::dev, "deviation (unit of the rate; U*s for tdev)")
      .def_readonly("lo", &AllanResult::lo, "lower bound of the 68.3 % interval")
      .def_readonly("hi", &AllanResult::hi, "upper bound of the 68.3 % interval")
      .def_readonly("n", &AllanResult::n, "number of terms of the estimator")
      .def_readonly("edf", &AllanResult::edf, "equivalent degrees of freedom")
      .def_readonly("alpha", &AllanResult::alpha, "identified power-law noise exponent")
      .def_readonly("m", &AllanResult::m, "averaging factor (tau = m / rate_hz)")
      .def("__len__", [](const AllanResult& r) { return r.points.size(); })
      .def("__repr__", &allan_repr);
  module.def("allan", &allan, py::arg("x"), py::arg("rate"), py::arg("deviation") = "oadev",
             py::arg("taus") = "octave", py::arg("data") = "rate", py::arg("edf") = "plausible", kAllanDoc);
}

}  // namespace stochnav::python

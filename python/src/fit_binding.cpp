// stochnav.fit: the IEEE 952 noise terms of a numpy record fitted to its overlapping Allan
// variance (Ceres), with 1-sigma uncertainties; the library calls of `stochnav fit`
// (cli/fit_command.cpp, without --window) on an array.

#include <fmt/format.h>

#include "arguments.hpp"
#include "bindings.hpp"
#include "noise_model_object.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_data.hpp"
#include "stochnav/fit/fit_noise_terms.hpp"
#include "stochnav/fit/fit_option_names.hpp"
#include "stochnav/fit/fit_result_json.hpp"
#include "stochnav/fit/gmwm_data.hpp"
#include "stochnav/fit/gmwm_fit.hpp"
#include "stochnav/fit/parameter_control_names.hpp"
#include "stochnav/model/reporting_units.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"
#include "stochnav/stats/tau_spacing_names.hpp"

namespace stochnav::python {
namespace {

/// `terms`: None (chosen automatically), a list of names or a comma-separated string.
std::vector<TermType> terms_argument(const py::object& terms) {
  std::vector<std::string> names;
  if (py::isinstance<py::str>(terms)) {
    names = split_comma_list(terms.cast<std::string>());
  } else {
    try {
      for (const auto& item : terms) names.push_back(py::str(item).cast<std::string>());
    } catch (const py::error_already_set&) {
      throw ConfigError(
          "terms: expected a list of term names (or None), e.g. "
          "[\"angle_random_walk\", \"rate_random_walk\"]");
    }
  }
  return parse_fit_terms(names, "terms");
}

PythonNoiseModel model_of(FitResult result) {
  PythonNoiseModel model;
  model.document = fit_result_to_json(result);
  model.model = std::move(result.model);
  model.sigma = std::move(result.sigma);
  return model;
}

void refuse_failed(const FitResult& result, bool keep_failed) {
  if (result.diagnostics.failed() && !keep_failed) {
    throw InputError(
        fmt::format("x: fit failed: {}; choose other terms, or pass "
                    "keep_failed=True to get the failed fit (flagged: .failed)",
                    result.diagnostics.failure()));
  }
}

/// start, fix and bound: the CLI's --start, --fix and --bound (TERM[#K].PARAM=V,...;
/// docs/allan.md, "Steering a fit"), for the given terms, in the reporting units of `unit`.
struct Steering {
  std::string start, fix, bound;
  std::vector<ParameterControl> controls(std::span<const TermType> terms, Unit unit) const {
    if (start.empty() && fix.empty() && bound.empty()) return {};
    if (terms.empty()) {
      throw ConfigError(
          "start, fix, bound: they steer the terms given; pass terms=[...] as well");
    }
    return parse_parameter_controls(terms, unit, start, fix, bound);
  }
};

/// method="gmwm": the library calls of `stochnav fit --method gmwm --terms ...` on an array.
PythonNoiseModel fit_by_gmwm(const py::object& x, double rate, const py::object& terms,
                             const std::string& data, const std::string& unit, bool robust,
                             const std::string& gauss_markov_sampling, bool keep_failed,
                             const Steering& steering) {
  if (terms.is_none()) {
    throw ConfigError(
        "terms: method=\"gmwm\" needs the terms, e.g. terms=[\"angle_random_walk\", "
        "\"gauss_markov\", \"rate_random_walk\"]");
  }
  GmwmOptions options;
  options.terms = terms_argument(terms);
  options.drop_terms_at_bound = true;  // as the CLI
  options.gauss_markov_sampling =
      parse_gauss_markov_sampling(gauss_markov_sampling, "gauss_markov_sampling");
  if (const auto problem = options.validate(); !problem.empty()) throw ConfigError(problem);
  const DataKind kind = data_kind_argument(data);
  const double rate_hz = rate_argument(rate);
  const Unit signal_unit = unit_argument(unit);
  options.controls = steering.controls(options.terms, signal_unit);
  const SampleArray samples(x, "x");
  FitResult result;
  {
    py::gil_scoped_release release;
    samples.check_finite();
    std::vector<double> values(samples.values().begin(), samples.values().end());
    if (kind == DataKind::kPhase) {
      for (std::size_t i = 0; i + 1 < values.size(); ++i) {
        values[i] = (values[i + 1] - values[i]) * rate_hz;
      }
      if (!values.empty()) values.pop_back();
    }
    result = fit_gmwm(gmwm_data_from_rate(values, rate_hz, signal_unit, robust, "x"), options);
  }
  refuse_failed(result, keep_failed);
  return model_of(std::move(result));
}

PythonNoiseModel fit(const py::object& x, double rate, const py::object& terms,
                     const std::string& method, const std::string& data, const std::string& unit,
                     const std::string& taus, const std::string& loss, const std::string& criterion,
                     bool keep_failed, bool robust, const std::string& gauss_markov_sampling,
                     const std::string& start, const std::string& fix, const std::string& bound) {
  const Steering steering{start, fix, bound};
  if (method == "gmwm") {
    return fit_by_gmwm(x, rate, terms, data, unit, robust, gauss_markov_sampling, keep_failed,
                       steering);
  }
  if (method != "avar") {
    throw ConfigError("method '" + method +
                      "': use \"avar\" (the Allan variance) or \"gmwm\" "
                      "(the Haar wavelet variance)");
  }
  if (robust || gauss_markov_sampling != "mean") {
    throw ConfigError("robust, gauss_markov_sampling: GMWM options; pass method=\"gmwm\"");
  }
  FitOptions options;
  if (!terms.is_none()) options.terms = terms_argument(terms);
  // As the CLI: a given term the data leave on its search bound is dropped (and reported).
  options.drop_terms_at_bound = true;
  options.loss = parse_robust_loss(loss, "loss");
  options.criterion = parse_information_criterion(criterion, "criterion");
  if (const auto problem = options.validate(); !problem.empty()) throw ConfigError(problem);
  const DataKind kind = data_kind_argument(data);
  const double rate_hz = rate_argument(rate);
  const Unit signal_unit = unit_argument(unit);
  options.controls = steering.controls(options.terms, signal_unit);
  const TauSpacing spacing = parse_tau_spacing(taus, "taus", false);
  const SampleArray samples(x, "x");
  FitResult result;
  {
    py::gil_scoped_release release;
    samples.check_finite();
    const double tau0_s = 1.0 / rate_hz;
    // The CLI's fit integrates with the serial reference sum (phase_from_rate) too: the same
    // sums as `stochnav fit`. On a text record the two agree to about 1e-14 relative, not
    // bitwise (the cause is not traced; the test holds 1e-9).
    const std::vector<double> phase =
        kind == DataKind::kPhase
            ? std::vector<double>(samples.values().begin(), samples.values().end())
            : phase_from_rate(samples.values(), tau0_s);
    const auto m_values = averaging_factors(Deviation::kOadev, spacing, phase.size(), tau0_s);
    if (m_values.size() < 2) {
      throw InputError(fmt::format("x: too short for a fit ({} samples); use a longer record",
                                   samples.values().size()));
    }
    const auto points = compute_deviation(Deviation::kOadev, phase, tau0_s, m_values);
    result = fit_noise_terms(
        fit_data_from_deviations(Deviation::kOadev, points, signal_unit, rate_hz), options);
  }
  refuse_failed(result, keep_failed);
  return model_of(std::move(result));
}

// One line per term of the vocabulary: its parameters in a gyro's reporting units (deg/h).
std::string term_vocabulary() {
  std::string text;
  for (TermType type : all_term_types()) {
    std::string parameters;
    for (const ParameterSpec& spec : parameter_specs(type)) {
      parameters += fmt::format("{}{} ({}){}", parameters.empty() ? "" : ", ", spec.name,
                                reported_unit_name(Quantity::kAngularRate, spec.dimension),
                                spec.optional ? " optional" : "");
    }
    const bool fittable = type != TermType::kNonstationary && type != TermType::kBiasStep &&
                          type != TermType::kAuxSensitivity;
    text += fmt::format("\n        {:<18} {}", term_type_name(type),
                        fittable ? parameters : "(time domain: found by stochnav.diagnose)");
  }
  return text;
}

std::string fit_doc() {
  return R"(Fit the IEEE 952 noise terms to the record's overlapping Allan variance (Ceres), or by
GMWM to its Haar wavelet variance (method="gmwm").

The library calls of `stochnav fit` on an array: OADEV at the taus, then a robust least-squares
fit in the log domain weighted by the estimator's covariance, terms chosen by an information
criterion unless given; each parameter with its 1-sigma uncertainty. method="gmwm": those of
`stochnav fit --method gmwm --terms ...` (docs/gmwm.md); terms are required, taus, loss and
criterion are not used.

Parameters
----------
x : 1-D array of float
    Rate samples in `unit` (or, data="phase", their integral); converted as for allan.
rate : float
    Sampling rate (Hz).
terms : list of str, str or None
    The terms to fit (a list, or a comma-separated string); None chooses them automatically
    among quantization, angle_random_walk, bias_instability, rate_random_walk, rate_ramp and
    gauss_markov. Power-law terms at most once; gauss_markov and sinusoid may repeat.
    The vocabulary, with each parameter in the reporting units of a gyro in deg/h
    (accelerometers: m/s in place of deg; plain data: the signal's own units):)" +
         term_vocabulary() + R"(
method : str
    "avar" (default) or "gmwm". Both drop a given term left on its search bound and refit
    (.diagnostics["dropped_terms"]).
data : str
    "rate" or "phase".
unit : str
    Unit of x: "deg/h", "deg/s", "rad/s", "m/s^2", "g" or "plain"; fixes the reporting units.
taus : str
    "octave", "decade" or "dense" averaging factors.
loss : str
    Robust loss: "huber" (default), "cauchy" or "none".
criterion : str
    Term selection: "bic" (default) or "aic".
keep_failed : bool
    Return a failed fit (a term on its search bound, an undetermined parameter, or a
    chi-square the terms cannot explain) flagged by .failed instead of raising InputError.
robust : bool
    method="gmwm": fit the robust wavelet variance (records with outliers).
gauss_markov_sampling : str
    method="gmwm": "mean" (samples are interval means, default) or "point" (a discrete AR1,
    the R gmwm package's).
start, fix, bound : str
    Steering, either method, as the CLI's --start, --fix and --bound (docs/allan.md, "Steering
    a fit"): "TERM[#K].PARAM=V,..." (starting values; fixed values, reported with sigma 0) and
    "TERM[#K].PARAM=LOW:HIGH,..." (search ranges), in the reporting units of `unit`, e.g.
    fix="gauss_markov#2.tau_c=100". They need `terms`.

Returns
-------
NoiseModel
    .terms with each parameter and its sigma (reporting units), .diagnostics, .to_json() as
    `stochnav fit --format json`, .allan_variance(tau), .wavelet_variance(scale_s).
)";
}

}  // namespace

void bind_fit(py::module_& module) {
  static const std::string doc = fit_doc();
  module.def("fit", &fit, py::arg("x"), py::arg("rate"), py::arg("terms") = py::none(),
             py::arg("method") = "avar", py::arg("data") = "rate", py::arg("unit") = "plain",
             py::arg("taus") = "octave", py::arg("loss") = "huber", py::arg("criterion") = "bic",
             py::arg("keep_failed") = false, py::arg("robust") = false,
             py::arg("gauss_markov_sampling") = "mean", py::arg("start") = "",
             py::arg("fix") = "", py::arg("bound") = "", doc.c_str());
}

}  // namespace stochnav::python

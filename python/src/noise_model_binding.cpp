// stochnav.NoiseModel: terms and parameters in the IEEE 952 reporting units of DESIGN.md, a
// fit's sigmas and diagnostics, JSON in and out, and the Allan and wavelet variances it implies.

#include <fmt/format.h>

#include <cmath>

#include "bindings.hpp"
#include "json_values.hpp"
#include "noise_model_object.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/io/json_document.hpp"
#include "stochnav/model/allan_variance.hpp"
#include "stochnav/model/noise_model_json.hpp"

namespace stochnav::python {

bool PythonNoiseModel::failed() const {
  const auto diagnostics = document.find("diagnostics");
  if (diagnostics == document.end() || !diagnostics->is_object()) return false;
  const auto flag = diagnostics->find("failed");
  return flag != diagnostics->end() && flag->is_boolean() && flag->get<bool>();
}

std::string PythonNoiseModel::failure() const {
  if (!failed()) return {};
  const auto& diagnostics = document["diagnostics"];
  const auto why = diagnostics.find("failure");
  return why != diagnostics.end() && why->is_string() ? why->get<std::string>() : "failed fit";
}

PythonNoiseModel noise_model_from_document(const nlohmann::json& document,
                                           const std::string& source) {
  PythonNoiseModel result;
  try {
    result.model = noise_model_from_json(document);
  } catch (const ConfigError& error) {
    if (source.empty()) throw;
    throw ConfigError(source + ": " + error.what());
  }
  result.document = document;
  return result;
}

PythonNoiseModel noise_model_argument(const py::handle& object, const std::string& what) {
  if (py::isinstance<PythonNoiseModel>(object)) return object.cast<PythonNoiseModel>();
  if (is_path(object)) {
    const auto path = path_from_python(object);
    return noise_model_from_document(read_json_document(path, what), path.string());
  }
  if (py::isinstance<py::dict>(object)) {
    return noise_model_from_document(json_from_python(object, what), what);
  }
  throw py::value_error(what + ": expected a stochnav.NoiseModel, a dict or the path of a JSON "
                               "file, got " +
                        std::string(py::str(py::type::of(object).attr("__name__"))));
}

namespace {

// The variance the model implies at each tau, in the model's unit squared.
std::vector<double> implied_allan_variance(const NoiseModel& model, std::span<const double> tau_s,
                                           double tau_scale, double variance_scale) {
  const double per_unit = si_per_unit(model.unit);
  std::vector<double> out;
  out.reserve(tau_s.size());
  for (double tau : tau_s) {
    out.push_back(variance_scale * allan_variance(model, tau * tau_scale) / (per_unit * per_unit));
  }
  return out;
}

py::object allan_variance_of(const PythonNoiseModel& self, const py::object& tau) {
  auto argument = real_argument(tau, "tau");
  return real_result(implied_allan_variance(self.model, argument.values, 1.0, 1.0),
                     argument.scalar);
}

py::object allan_deviation_of(const PythonNoiseModel& self, const py::object& tau) {
  auto argument = real_argument(tau, "tau");
  auto values = implied_allan_variance(self.model, argument.values, 1.0, 1.0);
  for (double& v : values) v = std::sqrt(v);
  return real_result(std::move(values), argument.scalar);
}

// wavelet_variance.hpp: the Haar wavelet variance at scale tau_j is AVAR(tau_j / 2) / 2.
py::object implied_wavelet_variance(const PythonNoiseModel& self, const py::object& scale_s) {
  auto argument = real_argument(scale_s, "scale_s");
  return real_result(implied_allan_variance(self.model, argument.values, 0.5, 0.5),
                     argument.scalar);
}

std::string model_repr(const PythonNoiseModel& self) {
  const NoiseModel& model = self.model;
  std::string text = fmt::format("<NoiseModel: {} at {:g} Hz, {} term(s){}>", unit_name(model.unit),
                                 model.rate_hz, model.terms.size(),
                                 self.failed() ? ", FAILED FIT: " + self.failure() : "");
  for (std::size_t i = 0; i < model.terms.size(); ++i) {
    const NoiseTerm* sigma = i < self.sigma.size() ? &self.sigma[i] : nullptr;
    text += "\n  " + describe(model.terms[i], quantity_of(model.unit), sigma);
  }
  return text;
}

PythonNoiseModel model_from_json(const py::object& json) {
  if (py::isinstance<py::str>(json) || py::isinstance<py::bytes>(json)) {
    return noise_model_from_document(
        parse_json_document(py::str(json).cast<std::string>(), "NoiseModel.from_json"), "");
  }
  return noise_model_from_document(json_from_python(json, "NoiseModel.from_json"), "");
}

constexpr const char* kNoiseModelDoc = R"(A noise model: the signal's unit, a nominal rate and IEEE 952 noise terms.

Made by stochnav.fit (with each parameter's 1-sigma and the fit's diagnostics), by
NoiseModel.from_json (a dict or JSON text) or NoiseModel.load (a file). Terms and parameters
are in the reporting units of the signal's unit; for a gyro in deg/h:

    quantization       Q (arcsec)                 AVAR 3 Q^2 / tau^2
    angle_random_walk  N (deg/sqrt(h))            AVAR (60 N)^2 / tau
    bias_instability   B (deg/h)                  flat floor 0.664 B in deviation
    rate_random_walk   K (deg/h/sqrt(h))          AVAR K^2 tau / 10800
    rate_ramp          R (deg/h^2)                AVAR R^2 tau^2 / (2 * 3600^2)
    gauss_markov       sigma (deg/h), tau_c (s)
    sinusoid           amplitude (deg/h), frequency_hz, optional phase_rad
    nonstationary      segments [{start, end (s), scale}]
    bias_step, aux_sensitivity  (deterministic: found by diagnose)

Accelerometers follow the same pattern with m/s in place of deg; plain data uses the signal's
own units (Q in signal*s, N in signal*sqrt(s), B in signal, ...).
)";

}  // namespace

void bind_noise_model(py::module_& module) {
  py::class_<PythonNoiseModel>(module, "NoiseModel", kNoiseModelDoc)
      .def_static("from_json", &model_from_json, py::arg("json"),
                  "A model from JSON text or a dict: the noise-model JSON of DESIGN.md, or the "
                  "output of `stochnav fit --format json` / NoiseModel.to_json() (sigmas and "
                  "diagnostics kept). Raises ConfigError naming the JSON pointer at fault.")
      .def_static(
          "load", [](const py::object& path) { return noise_model_argument(path, "the model"); },
          py::arg("path"), "A model from a JSON file (as from_json).")
      .def_property_readonly(
          "units", [](const PythonNoiseModel& self) { return unit_name(self.model.unit); },
          "unit of the signal: deg/h, deg/s, rad/s, m/s^2, g or plain")
      .def_property_readonly(
          "rate_hz", [](const PythonNoiseModel& self) { return self.model.rate_hz; },
          "nominal sampling rate (Hz)")
      .def_property_readonly(
          "terms",
          [](const PythonNoiseModel& self) { return python_from_json(self.document.at("terms")); },
          "the terms as dicts in reporting units, e.g. {\"type\": \"angle_random_walk\", "
          "\"N\": 0.05, \"N_sigma\": 0.001} (N_sigma: a fit's 1-sigma; None when undetermined)")
      .def_property_readonly(
          "term_types",
          [](const PythonNoiseModel& self) {
            std::vector<std::string> names;
            for (const auto& term : self.model.terms) {
              names.emplace_back(term_type_name(term_type(term)));
            }
            return names;
          },
          "the terms' type names, in order")
      .def_property_readonly(
          "diagnostics",
          [](const PythonNoiseModel& self) -> py::object {
            const auto found = self.document.find("diagnostics");
            if (found == self.document.end()) return py::none();
            return python_from_json(*found);
          },
          "a fit's diagnostics (chi_square, criterion, chosen_terms, slope_readoffs, failed, "
          "failure, ...) as a dict; None for a model not fitted")
      .def_property_readonly("failed", &PythonNoiseModel::failed,
                             "True for a fit flagged as failed (see diagnostics['failure'])")
      .def(
          "to_json",
          [](const PythonNoiseModel& self, int indent) { return self.document.dump(indent) + "\n"; },
          py::arg("indent") = 2,
          "The JSON `stochnav fit --format json` writes (a model not fitted: as given).")
      .def(
          "to_dict",
          [](const PythonNoiseModel& self) { return python_from_json(self.document); },
          "to_json() as a dict")
      .def("allan_variance", &allan_variance_of, py::arg("tau"),
           "Allan variance the model implies at tau (s; a number or an array), in the model's "
           "unit squared (closed forms of DESIGN.md).")
      .def("allan_deviation", &allan_deviation_of, py::arg("tau"),
           "sqrt(allan_variance(tau)), in the model's unit.")
      .def("wavelet_variance", &implied_wavelet_variance, py::arg("scale_s"),
           "Haar wavelet variance the model implies at scale_s (s), in the model's unit squared: "
           "AVAR(scale_s / 2) / 2, comparable with stochnav.wv.")
      .def(
          "equals",
          [](const PythonNoiseModel& self, const PythonNoiseModel& other, double rel_tol) {
            return equals(self.model, other.model, rel_tol);
          },
          py::arg("other"), py::arg("rel_tol") = 1e-9,
          "Same unit, rate and terms with every parameter within rel_tol.")
      .def("__repr__", &model_repr);
}

}  // namespace stochnav::python

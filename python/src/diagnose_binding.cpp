// stochnav.diagnose: what a noise model misses in a numpy record, named, added and the gap shown
// shrinking; the library call of `stochnav diagnose --input --model` (cli/diagnose_command.cpp)
// returning report.json as a dict (no files, no plots).

#include "arguments.hpp"
#include "bindings.hpp"
#include "json_values.hpp"
#include "noise_model_object.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/diagnose.hpp"
#include "stochnav/diagnose/report_json.hpp"

namespace stochnav::python {
namespace {

std::vector<AuxChannel> aux_argument(const py::object& aux, std::size_t samples) {
  std::vector<AuxChannel> channels;
  if (aux.is_none()) return channels;
  if (!py::isinstance<py::dict>(aux)) {
    throw py::value_error("aux: expected a dict of auxiliary channels, e.g. "
                          "{\"temperature_c\": array}, one value per sample of x");
  }
  for (const auto& [name, column] : aux.cast<py::dict>()) {
    const std::string label = "aux[\"" + py::str(name).cast<std::string>() + "\"]";
    const SampleArray values(py::reinterpret_borrow<py::object>(column), label);
    values.check_finite(0);
    if (values.values().size() != samples) {
      throw ConfigError(label + ": " + std::to_string(values.values().size()) +
                        " values for " + std::to_string(samples) +
                        " samples of x; give one value per sample");
    }
    channels.push_back({py::str(name).cast<std::string>(),
                        std::vector<double>(values.values().begin(), values.values().end())});
  }
  return channels;
}

py::object diagnose_record(const py::object& x, double rate, const py::object& model_argument,
                           const std::string& data, const py::object& unit, int seeds,
                           const py::object& seed, int max_iterations, double alpha,
                           long long windows, const py::object& aux) {
  if (windows < 0) throw ConfigError("windows: " + std::to_string(windows) + "; expected 4 or more");
  const PythonNoiseModel model = noise_model_argument(model_argument, "model");
  DiagnoseOptions options;
  options.seeds = seeds;
  options.seed = seed_argument(seed, "seed");
  options.max_iterations = max_iterations;
  options.alpha = alpha;
  options.windows = static_cast<std::size_t>(windows);
  if (const auto problem = options.validate(); !problem.empty()) throw ConfigError(problem);
  Record record;
  record.rate_hz = rate_argument(rate);
  record.kind = data_kind_argument(data);
  record.unit = unit.is_none() ? model.model.unit : unit_argument(unit.cast<std::string>());
  record.source = "x";
  record.column = "x";
  if (quantity_of(model.model.unit) != quantity_of(record.unit)) {
    throw ConfigError("model: the model is in " + unit_name(model.model.unit) +
                      " but x in " + unit_name(record.unit) +
                      "; pass a matching unit (or leave it out to use the model's)");
  }
  const SampleArray samples(x, "x");
  const std::vector<AuxChannel> channels = aux_argument(aux, samples.values().size());
  nlohmann::json report;
  {
    py::gil_scoped_release release;
    samples.check_finite();
    record.values.assign(samples.values().begin(), samples.values().end());
    report = diagnose_report_json(diagnose(record, model.model, options, channels));
  }
  return python_from_json(report);
}

constexpr const char* kDiagnoseDoc = R"(Find what a noise model misses in a record, name it, add it, and show the gap shrink.

The discrepancy workflow of `stochnav diagnose` (docs/diagnose.md): the record's Allan
variance (with its estimator covariance) and DAVAR against the model's closed forms and
simulated records; while they disagree, the missing effect is named from the vocabulary of
stochnav.NoiseModel, fitted, added and the gap recomputed.

Parameters
----------
x : 1-D array of float
    Rate samples in `unit` (or, data="phase", their integral).
rate : float
    Sampling rate (Hz).
model : NoiseModel, dict or path
    The model to test.
data : str
    "rate" or "phase".
unit : str, optional
    Unit of x; default the model's.
seeds : int
    Simulated records per model assessment (0: none, else >= 2).
seed : int
    First simulation seed.
max_iterations : int
    Most terms to add.
alpha : float
    False-alarm probability of the consistency test.
windows : int
    Windows of the stationarity test (>= 4).
aux : dict, optional
    Auxiliary channels of the record ({"temperature_c": array}, one value per sample), tested
    for a bias linear in each (aux_sensitivity).

Returns
-------
dict
    report.json of DESIGN.md: consistent, gap_initial, gap_final, iterations [{effect,
    evidence, tau_range_s, time_range_s, added_term, gap_before, gap_after}], final_model
    (stochnav.NoiseModel.from_json(report["final_model"]) makes it a model).
)";

}  // namespace

void bind_diagnose(py::module_& module) {
  module.def("diagnose", &diagnose_record, py::arg("x"), py::arg("rate"), py::arg("model"),
             py::arg("data") = "rate", py::arg("unit") = py::none(), py::arg("seeds") = 6,
             py::arg("seed") = 1, py::arg("max_iterations") = 4, py::arg("alpha") = 1e-3,
             py::arg("windows") = 32, py::arg("aux") = py::none(), kDiagnoseDoc);
}

}  // namespace stochnav::python

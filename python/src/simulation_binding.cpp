// stochnav.simulate_noise and stochnav.simulate_scenario: records with known truth, from the
// library calls of `stochnav simulate noise | scenario` (cli/simulate_command.cpp).

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "arguments.hpp"
#include "bindings.hpp"
#include "json_values.hpp"
#include "noise_model_object.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/core/work_limits.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"
#include "stochnav/scenario/scenario_writer.hpp"
#include "stochnav/sim/noise_generator.hpp"

namespace stochnav::python {
namespace {

// duration_s and rate_hz as the CLI checks --duration and --rate (core/work_limits.hpp).
void check_simulated_length(double duration_s, double rate_hz) {
  if (!(duration_s > 0.0) || !std::isfinite(duration_s)) {
    throw ConfigError("duration_s must be a finite number of seconds > 0");
  }
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw ConfigError("rate_hz must be a finite number of Hz > 0");
  }
  if (rate_hz > limits::kMaxSimulatedRateHz) {
    throw ConfigError(fmt::format("rate_hz {:g} is above the limit of {:g} Hz; give a lower rate "
                                  "(docs/reliability.md, Limits on work)",
                                  rate_hz, limits::kMaxSimulatedRateHz));
  }
  const double samples = std::round(duration_s * rate_hz);
  if (samples > limits::kMaxSimulatedSamples) {
    throw ConfigError(fmt::format("duration_s {:g} at rate_hz {:g} is {:.3g} samples, above the "
                                  "limit of {:.3g} per record; simulate several shorter records "
                                  "with different seeds (docs/reliability.md, Limits on work)",
                                  duration_s, rate_hz, samples, limits::kMaxSimulatedSamples));
  }
  if (samples < 2) throw ConfigError("duration_s x rate_hz gives fewer than 2 samples");
}

py::array_t<double> simulate_noise_record(const py::object& model_argument, double duration_s,
                                          double rate_hz, const py::object& seed_object,
                                          bool accept_failed) {
  const std::uint64_t seed = seed_argument(seed_object, "seed");
  const PythonNoiseModel model = noise_model_argument(model_argument, "model");
  if (model.failed() && !accept_failed) {
    throw ConfigError("model: a failed fit (" + model.failure() + "); refit the record, or pass "
                      "accept_failed=True to simulate it anyway");
  }
  check_simulated_length(duration_s, rate_hz);
  std::vector<double> samples;
  {
    py::gil_scoped_release release;
    samples = simulate_noise(model.model, duration_s, rate_hz, seed);
    const double per_unit = si_per_unit(model.model.unit);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      samples[k] /= per_unit;  // in the model's unit, as `simulate noise` writes it
      if (!std::isfinite(samples[k])) {
        throw ConfigError(fmt::format("model: the simulated record is not finite at t = {:g} s "
                                      "(the parameters are too large for a double); use "
                                      "parameters of a physical size",
                                      static_cast<double>(k) / rate_hz));
      }
    }
  }
  return to_numpy(std::move(samples));
}

std::string simulate_scenario_folder(const py::object& config, const py::object& out,
                                     const py::object& seed, bool progress) {
  const JsonDocument document = json_document(config, "the scenario config");
  const ScenarioConfig scenario =
      scenario_config_from_json(document.json, document.file.string());
  ScenarioOutputOptions options;
  options.out_dir = path_from_python(out);
  options.seed = seed.is_none() ? scenario.seed : seed_argument(seed, "seed");
  options.progress = progress;
  options.source = document.file.string();
  {
    py::gil_scoped_release release;
    write_scenario_outputs(scenario, options);
  }
  return options.out_dir.string();
}

constexpr const char* kSimulateNoiseDoc = R"(A noise record simulated from a noise model (`stochnav simulate noise`, one axis).

Sample k is the mean of the model's continuous-time rate over [k, k + 1) / rate_hz, so the
record's expected Allan variance equals the model's closed form at every tau.

Parameters
----------
model : NoiseModel, dict or path
    The noise model (DESIGN.md JSON, or a fit).
duration_s : float
    Record length (s); round(duration_s * rate_hz) samples.
rate_hz : float
    Sampling rate (Hz), at most 1e6; at most 1e9 samples.
seed : int
    Random seed (>= 0): the same seed gives the same record.
accept_failed : bool
    Simulate a model flagged as a failed fit.

Returns
-------
numpy.ndarray
    The rate samples in the model's unit (model.units).
)";

constexpr const char* kSimulateScenarioDoc = R"(Simulate an MWD scenario (vibration table or drilling) with truth (`stochnav simulate scenario`).

Parameters
----------
config : dict or path
    The scenario config (configs/scenarios/*.json); a dict's relative paths start in the
    working folder.
out : str or path
    Output folder (created if missing): imu.csv, truth.csv, aids.csv, scenario.json.
seed : int, optional
    Random seed (default: the config's "seed").
progress : bool
    Draw a progress bar on standard error.

Returns
-------
str
    The output folder, ready for stochnav.run(config, data=out).
)";

}  // namespace

void bind_simulation(py::module_& module) {
  module.def("simulate_noise", &simulate_noise_record, py::arg("model"), py::arg("duration_s"),
             py::arg("rate_hz"), py::arg("seed"), py::arg("accept_failed") = false,
             kSimulateNoiseDoc);
  module.def("simulate_scenario", &simulate_scenario_folder, py::arg("config"), py::arg("out"),
             py::arg("seed") = py::none(), py::arg("progress") = false, kSimulateScenarioDoc);
}

}  // namespace stochnav::python

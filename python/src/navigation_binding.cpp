// The navigation runs behind stochnav.run and stochnav.compare (python/stochnav/_navigation.py):
// the library calls of `stochnav run` and `stochnav compare` (cli/run_command.cpp,
// cli/compare_command.cpp) writing into a folder, the summaries returned as dicts.

#include <fmt/format.h>

#include <optional>

#include "arguments.hpp"
#include "bindings.hpp"
#include "json_values.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/comparison.hpp"
#include "stochnav/experiment/experiment_config.hpp"
#include "stochnav/experiment/navigation_run.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav::python {
namespace {

/// The run config of a dict or file, with `data` (a recording folder) replacing its "data".
plugin::RunConfig run_config_argument(const py::object& config, const py::object& data) {
  std::optional<plugin::DataConfig> data_config;
  if (!data.is_none()) data_config = plugin::data_from_folder(path_from_python(data));
  const JsonDocument document = json_document(config, "the run config");
  return plugin::parse_run_config(document.json, document.folder, data_config);
}

py::dict run_into_folder(const py::object& config, const py::object& data, const py::object& out,
                         bool plot, bool progress) {
  const plugin::RunConfig run_config = run_config_argument(config, data);
  NavigationRunOptions options;
  options.out_dir = path_from_python(out);
  options.plot = plot;
  options.progress = progress;
  NavigationRunResult result;
  {
    py::gil_scoped_release release;
    result = run_navigation(run_config, options);
  }
  py::dict summary;
  summary["metrics"] = python_from_json(result.metrics_json());
  summary["epochs"] = result.epochs;
  summary["duration_s"] = result.duration_s;
  summary["wall_seconds"] = result.wall_seconds;
  summary["has_truth"] = result.has_truth;
  summary["filter_ok"] = result.health.ok();
  summary["consistency_line"] = result.consistency_line;
  summary["warnings"] = result.warnings;
  return summary;
}

py::dict compare_into_folder(const py::object& experiment, const py::object& seeds,
                             const py::object& out, bool progress) {
  const JsonDocument document = json_document(experiment, "the experiment");
  ExperimentConfig config = experiment_config_from_json(document.json, document.file);
  if (!seeds.is_none()) {
    if (!config.scenario_config) {
      throw ConfigError("seeds: the experiment's data is not simulated; drop seeds");
    }
    config.seeds.clear();
    for (const auto& seed : seeds) config.seeds.push_back(seed_argument(seed, "seeds"));
  }
  check_work_limits(config);
  const std::filesystem::path out_dir = path_from_python(out);
  py::dict summary;
  if (config.sweep) {
    nlohmann::json sweep;
    {
      py::gil_scoped_release release;
      sweep = run_sweep(config, out_dir, progress);
    }
    summary["sweep"] = python_from_json(sweep);
    return summary;
  }
  std::string table;
  nlohmann::json results;
  {
    py::gil_scoped_release release;
    const ComparisonResult result = run_comparison(config, out_dir, progress);
    write_comparison(result, config, out_dir);
    table = comparison_table(result, config);
    results = comparison_json(result);
  }
  summary["results"] = python_from_json(results);
  summary["table"] = table;
  return summary;
}

}  // namespace

void bind_navigation(py::module_& module) {
  module.def("_run_into_folder", &run_into_folder, py::arg("config"), py::arg("data"),
             py::arg("out"), py::arg("plot"), py::arg("progress"),
             "stochnav.run's library call: `stochnav run` writing into `out`; returns the "
             "summary (metrics.json as a dict, epochs, ...).");
  module.def("_compare_into_folder", &compare_into_folder, py::arg("experiment"),
             py::arg("seeds"), py::arg("out"), py::arg("progress"),
             "stochnav.compare's library call: `stochnav compare` writing into `out`; returns "
             "{'results': results.json, 'table': table.md} or {'sweep': sweep.json}.");
}

}  // namespace stochnav::python

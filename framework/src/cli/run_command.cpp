// stochnav run CONFIG.json --out DIR [--data DIR]: one navigation run
// (experiment/navigation_run.hpp).

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "standard_output.hpp"
#include "stochnav/experiment/navigation_run.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav::cli {
namespace {

struct RunArguments {
  std::string config;
  std::string out;
  std::string data;
  bool no_plot = false;
};

/// `error_model`: the run config's "survey/error_model" (its file is named unless "none").
void print_summary(const NavigationRunResult& result, const std::string& out,
                   const std::string& error_model) {
  std::string text = fmt::format("{} epochs ({:.0f} s of data) in {:.2f} s; filter health: {}\n",
                           result.epochs, result.duration_s, result.wall_seconds,
                           result.health.ok() ? "ok" : "TROUBLE (see metrics.json)");
  if (result.has_truth) {
    text += fmt::format("{:<22} {:>14} {:>14}\n", "error", "max |error|", "rms");
    for (std::size_t i = 0; i < kErrorMetricCount; ++i) {
      text += fmt::format("{:<22} {:>14.6g} {:>14.6g}\n", kErrorMetricNames[i],
                               result.statistics.max_abs(i), result.statistics.rms(i));
    }
  } else {
    text += "no truth: errors not scored; the aids' innovations judge the run\n";
  }
  if (!result.consistency_line.empty()) text += result.consistency_line + '\n';
  for (const std::string& warning : result.warnings) text += warning + '\n';
  text += fmt::format("{} survey station(s)\n", result.survey_stations);
  text += "wrote " + out + "/{nav,biases,covariance,states,innovations" +
          (result.has_truth ? ",errors" : "") + ",survey}.csv, metrics.json" +
          (error_model != "none" ? ", iscwsa_covariance.csv" : "") +
          (result.error_series.size() > 1 ? ", errors.png" : "") + '\n';
  write_standard_output(text);
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto arguments = std::make_shared<RunArguments>();
  CLI::App* command =
      app.add_subcommand("run", "Run the MWD navigation filter on a record or simulated scenario");
  command->add_option("config", arguments->config, "Run config (JSON)")->required();
  command->add_option("--out", arguments->out, "Output folder")->required();
  command->add_option("--data", arguments->data,
                      "Recording folder replacing the config's \"data\": imu.csv, optional "
                      "aids.csv and truth.csv");
  command->add_flag("--no-plot", arguments->no_plot, "Do not draw errors.png");
  command->callback([arguments] {
    std::optional<plugin::DataConfig> data;
    if (!arguments->data.empty()) data = plugin::data_from_folder(arguments->data);
    const plugin::RunConfig config = plugin::read_run_config(arguments->config, data);
    NavigationRunOptions options;
    options.out_dir = arguments->out;
    options.progress = true;
    options.plot = !arguments->no_plot;
    print_summary(run_navigation(config, options), arguments->out, config.survey.error_model);
  });
}

}  // namespace stochnav::cli

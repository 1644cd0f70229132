// stochnav run CONFIG.json --out DIR: one navigation run (experiment/navigation_run.hpp).

#include <unistd.h>

#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "stochnav/experiment/navigation_run.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav::cli {
namespace {

struct RunArguments {
  std::string config;
  std::string out;
  bool no_plot = false;
};

void print_summary(const NavigationRunResult& result, const std::string& out) {
  std::cout << fmt::format("{} epochs ({:.0f} s of data) in {:.2f} s; filter health: {}\n",
                           result.epochs, result.duration_s, result.wall_seconds,
                           result.health.ok() ? "ok" : "TROUBLE (see metrics.json)");
  std::cout << fmt::format("{:<22} {:>14} {:>14}\n", "error", "max |error|", "rms");
  for (std::size_t i = 0; i < kErrorMetricCount; ++i) {
    std::cout << fmt::format("{:<22} {:>14.6g} {:>14.6g}\n", kErrorMetricNames[i],
                             result.statistics.max_abs(i), result.statistics.rms(i));
  }
  std::cout << "wrote " << out << "/{nav,biases,covariance,innovations,errors}.csv, metrics.json"
            << (result.error_series.size() > 1 ? ", errors.png" : "") << '\n';
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto arguments = std::make_shared<RunArguments>();
  CLI::App* command =
      app.add_subcommand("run", "Run the MWD navigation filter on a record or simulated scenario");
  command->add_option("config", arguments->config, "Run config (JSON)")->required();
  command->add_option("--out", arguments->out, "Output folder")->required();
  command->add_flag("--no-plot", arguments->no_plot, "Do not draw errors.png");
  command->callback([arguments] {
    const plugin::RunConfig config = plugin::read_run_config(arguments->config);
    NavigationRunOptions options;
    options.out_dir = arguments->out;
    options.progress = ::isatty(STDERR_FILENO) != 0;
    options.plot = !arguments->no_plot;
    print_summary(run_navigation(config, options), arguments->out);
  });
}

}  // namespace stochnav::cli

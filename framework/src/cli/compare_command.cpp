// stochnav compare EXPERIMENT.json --out DIR: filter variants x Monte-Carlo seeds
// (experiment/comparison.hpp).

#include <iostream>
#include <memory>

#include "command_support.hpp"
#include "commands.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/comparison.hpp"

namespace stochnav::cli {

void add_compare_command(CLI::App& app) {
  struct Arguments {
    std::string experiment;
    std::string out;
    std::vector<std::uint64_t> seeds;
    bool full_scenario = false;
  };
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "compare", "Compare filter variants (noise models) on the same data over Monte-Carlo seeds");
  command->add_option("experiment", arguments->experiment, "Experiment config (JSON)")
      ->required();
  command->add_option("--out", arguments->out, "Output folder")->required();
  command->add_option("--seeds", arguments->seeds,
                      "Override the experiment's seeds (simulated data only), e.g. --seeds 1 2 3")
      ->check(whole_number());
  command->add_flag("--full-scenario", arguments->full_scenario,
                    "Simulate the scenario as its config says, ignoring the experiment's "
                    "data/scenario_overrides (e.g. the whole 36 h drilling run)");
  command->callback([arguments] {
    ExperimentConfig config = read_experiment_config(arguments->experiment);
    if (arguments->full_scenario) config.scenario_overrides = nlohmann::json::object();
    if (!arguments->seeds.empty()) {
      if (!config.scenario_config) {
        throw ConfigError("--seeds: the experiment's data is not simulated; drop --seeds");
      }
      config.seeds = arguments->seeds;
    }
    check_work_limits(config);
    if (config.sweep) {
      const nlohmann::json sweep = run_sweep(config, arguments->out, true);
      std::cout << "wrote " << arguments->out << "/sweep.json, sweep.png, sweep_pairs.png and "
                << sweep["levels"].size() << " level folders (level_<i>/)\n";
      return;
    }
    const ComparisonResult result = run_comparison(config, arguments->out, true);
    write_comparison(result, config, arguments->out);
    std::cout << comparison_table(result, config);
    std::cout << "\nwrote " << arguments->out << "/results.json, table.md, metrics.png, "
              << "errors_<variant>.png (" << result.wall_seconds << " s)\n";
  });
}

}  // namespace stochnav::cli

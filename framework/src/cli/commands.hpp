#pragma once
// Registration of the stochnav subcommands. Each adds itself to the application and sets the
// callback that runs it; the callbacks throw InputError / ConfigError for exit code 2.

#include <CLI/CLI.hpp>

namespace stochnav::cli {

void add_allan_command(CLI::App& app);
void add_davar_command(CLI::App& app);
void add_diagnose_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_plugins_command(CLI::App& app);
void add_wv_command(CLI::App& app);
void add_survey_command(CLI::App& app);

}  // namespace stochnav::cli

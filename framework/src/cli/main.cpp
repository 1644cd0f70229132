// stochnav: the command-line tool. Exit codes: 0 success, 2 bad input or configuration (one
// line on stderr saying what, where and how to fix it) or an output that could not be written
// (standard output included), 1 internal failure.

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "commands.hpp"
#include "message_text.hpp"
#include "standard_output.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/core/temporary_files.hpp"
#include "stochnav/version.hpp"

namespace {

int run(int argc, char** argv) {
  using stochnav::cli::printable;
  CLI::App app{"stochnav: inertial-sensor noise modelling for Kalman filters"};
  app.set_version_flag("--version", std::string(stochnav::kVersion));
  app.require_subcommand(1);
  stochnav::cli::add_allan_command(app);
  stochnav::cli::add_davar_command(app);
  stochnav::cli::add_diagnose_command(app);
  stochnav::cli::add_fit_command(app);
  stochnav::cli::add_simulate_command(app);
  stochnav::cli::add_run_command(app);
  stochnav::cli::add_compare_command(app);
  stochnav::cli::add_plugins_command(app);
  stochnav::cli::add_wv_command(app);
  stochnav::cli::add_survey_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& success) {
    return app.exit(success);
  } catch (const CLI::ParseError& error) {
    std::cerr << "stochnav: error: " << printable(error.what()) << " (see stochnav --help)\n";
    return 2;
  } catch (const stochnav::InputError& error) {
    std::cerr << "stochnav: error: " << printable(error.what()) << '\n';
    return 2;
  } catch (const stochnav::ConfigError& error) {
    std::cerr << "stochnav: error: " << printable(error.what()) << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "stochnav: internal error: " << printable(error.what()) << '\n';
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Before anything opens a file: a closed standard output must not become the first output
  // file's descriptor.
  stochnav::cli::reserve_standard_streams();
  // Before any thread starts: SIGINT/SIGTERM remove the temporary files of unfinished outputs.
  stochnav::install_signal_cleanup();
  const int code = run(argc, argv);
  // What the command (or --help) wrote must have reached standard output: a failed write is
  // an error even after the command succeeded. One line on stderr: a command that already
  // failed has said why.
  try {
    stochnav::cli::close_standard_output();
  } catch (const stochnav::InputError& error) {
    if (code != 0) return code;
    std::cerr << "stochnav: error: " << stochnav::cli::printable(error.what()) << '\n';
    return 2;
  }
  return code;
}

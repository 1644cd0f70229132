#pragma once
// Pieces shared by the stochnav subcommands: input options, output files, formats.

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>

#include "stochnav/core/progress_bar.hpp"

#include "stochnav/io/record.hpp"

namespace stochnav::cli {

/// The input options common to allan, davar, fit and diagnose (DESIGN.md CLI contract).
struct InputArguments {
  std::string path;
  std::string column;
  std::optional<double> rate_hz;
  std::string data = "rate";
  std::string unit = "plain";
  int binary_channels = 1;

  ReadOptions to_read_options() const;
};

void add_input_options(CLI::App& command, InputArguments& arguments);

/// Progress of reading `options`' file, shown only when standard error is a terminal: a bar
/// over its bytes (a count of bytes for .gz, whose length is known only at its end), counted
/// through options.bytes_read. `label` names the command ("allan: reading").
std::unique_ptr<ProgressTicker> reading_progress(const std::string& label, ReadOptions& options);

enum class OutputFormat { kTable, kCsv, kJson };
void add_format_option(CLI::App& command, std::string& format);

/// Accepts a whole number >= 1 as typed ("-5" is refused, not wrapped into a huge count).
CLI::Validator positive_count();

/// Accepts a finite number > 0 (a rate), with a message that says so (CLI11's PositiveNumber
/// printed its bound, the largest double, in 309 digits).
CLI::Validator positive_number();
/// Accepts a whole number in [0, 2^64 - 1] as typed: digits only, so "-5" is refused instead of
/// wrapped into 2^64 - 5 (seeds).
CLI::Validator whole_number();

/// Accepts a whole number in [low, high] as typed; beyond `high` the message gives the limit
/// (core/work_limits.hpp) and where it is documented.
CLI::Validator whole_number_in(std::uint64_t low, std::uint64_t high);
OutputFormat parse_format(const std::string& format);

/// Writes `content` to `path` through a temporary file renamed into place, so a failure never
/// leaves a half-written file. An empty path or "-" writes to standard output.
void write_output(const std::string& path, const std::string& content);

}  // namespace stochnav::cli

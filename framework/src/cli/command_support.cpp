#include "command_support.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <fstream>
#include <string_view>

#include "stochnav/core/errors.hpp"
#include "standard_output.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav::cli {

ReadOptions InputArguments::to_read_options() const {
  ReadOptions options;
  options.path = path;
  options.column = column;
  options.rate_hz = rate_hz;
  if (data == "rate") {
    options.kind = DataKind::kRate;
  } else if (data == "phase") {
    options.kind = DataKind::kPhase;
  } else {
    throw ConfigError("--data '" + data + "': use rate or phase");
  }
  options.unit = parse_unit(unit);
  options.binary_channels = binary_channels;
  return options;
}

std::unique_ptr<ProgressTicker> reading_progress(const std::string& label, ReadOptions& options) {
  std::error_code error;
  const bool compressed = std::string_view(options.path).ends_with(".gz");
  const auto size = compressed ? 0 : std::filesystem::file_size(options.path, error);
  auto ticker = std::make_unique<ProgressTicker>(label, error ? 0 : size,
                                                 standard_error_is_terminal());
  options.bytes_read = ticker->counter();
  return ticker;
}

void add_input_options(CLI::App& command, InputArguments& arguments) {
  command.add_option("--input", arguments.path, "Record file: .csv, text (# comments), .f64/.f32, .gz")
      ->required();
  command.add_option("--column", arguments.column, "Column by name or 0-based index");
  command.add_option("--rate", arguments.rate_hz, "Sampling rate in Hz (when there is no t column)");
  command.add_option("--data", arguments.data, "rate (gyro rate, frequency) or phase (its integral)")
      ->capture_default_str();
  command.add_option("--unit", arguments.unit, "deg/h, deg/s, rad/s, m/s^2, g or plain")
      ->capture_default_str();
  command.add_option("--columns", arguments.binary_channels,
                     "Interleaved channels per epoch in .f64/.f32 files")
      ->capture_default_str()
      ->check(positive_count());
}

void add_format_option(CLI::App& command, std::string& format) {
  command.add_option("--format", format, "table, csv or json")->capture_default_str();
}

OutputFormat parse_format(const std::string& format) {
  if (format == "table") return OutputFormat::kTable;
  if (format == "csv") return OutputFormat::kCsv;
  if (format == "json") return OutputFormat::kJson;
  throw ConfigError("--format '" + format + "': use table, csv or json");
}

void write_output(const std::string& path, const std::string& content) {
  if (path.empty() || path == "-") {
    write_standard_output(content);
    return;
  }
  write_file_atomically(path, content);
}

namespace {

bool all_digits(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
}

// The value of a digit string, or nothing when it does not fit in 64 bits.
std::optional<std::uint64_t> parse_whole(const std::string& text) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

CLI::Validator whole_number() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        if (all_digits(text) && parse_whole(text)) return {};
        return "'" + text + "' is not a whole number from 0 to 18446744073709551615";
      },
      "UINT >= 0");
}

CLI::Validator whole_number_in(std::uint64_t low, std::uint64_t high) {
  return CLI::Validator(
      [low, high](const std::string& text) -> std::string {
        const auto value = all_digits(text) ? parse_whole(text) : std::nullopt;
        if (!value || *value < low) {
          return "'" + text + "' is not a whole number from " + std::to_string(low) + " to " +
                 std::to_string(high);
        }
        if (*value > high) {
          return text + " is above the limit of " + std::to_string(high) +
                 " (docs/reliability.md, Limits on work); give at most " + std::to_string(high);
        }
        return {};
      },
      "UINT in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
}

CLI::Validator positive_count() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        if (digits && text.find_first_not_of('0') != std::string::npos) return {};
        return "'" + text + "' is not a whole number >= 1";
      },
      "COUNT >= 1");
}

CLI::Validator positive_number() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        double value = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error == std::errc() && end == text.data() + text.size() && value > 0.0 &&
            std::isfinite(value)) {
          return {};
        }
        return "'" + text + "' is not a positive, finite number";
      },
      "NUMBER > 0");
}

}  // namespace stochnav::cli

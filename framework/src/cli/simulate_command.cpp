// stochnav simulate noise | scenario: records with known truth.

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>

#include "command_support.hpp"
#include "commands.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/core/work_limits.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"
#include "stochnav/scenario/scenario_writer.hpp"
#include "stochnav/sim/noise_generator.hpp"
#include "stochnav/sim/normal_generator.hpp"
#include "stochnav/io/json_document.hpp"

namespace stochnav::cli {
namespace {

struct NoiseArguments {
  std::string model_path;
  double duration_s = 0.0;
  double rate_hz = 0.0;
  std::uint64_t seed = 0;
  std::string out;
  std::vector<std::string> columns;
  bool accept_failed = false;
};

struct Axis {
  std::string column;
  NoiseModel model;
};

// A model `stochnav fit` flagged as failed ("diagnostics": {"failed": true, "failure": why})
// is refused unless --accept-failed: its terms are not what the record shows.
void refuse_failed_fit(const nlohmann::json& model, const std::string& pointer,
                       const NoiseArguments& arguments) {
  if (arguments.accept_failed || !model.is_object() || !model.contains("diagnostics")) return;
  const nlohmann::json& diagnostics = model["diagnostics"];
  if (!diagnostics.is_object() || !diagnostics.contains("failed")) return;
  if (!diagnostics["failed"].is_boolean()) {
    throw ConfigError(arguments.model_path + ": " + pointer +
                      "/diagnostics/failed: expected true or false");
  }
  if (!diagnostics["failed"].get<bool>()) return;
  std::string why;
  if (diagnostics.contains("failure") && diagnostics["failure"].is_string()) {
    why = " (" + diagnostics["failure"].get<std::string>() + ")";
  }
  throw ConfigError(arguments.model_path + ": " + pointer + "/diagnostics/failed: the model is a "
                    "failed fit" + why + "; refit the record, or give --accept-failed to "
                    "simulate it anyway");
}

// A model file is one noise model (one column) or {"axes": {"name": model, ...}}.
std::vector<Axis> read_axes(const NoiseArguments& arguments) {
  const nlohmann::json document = read_json_document(arguments.model_path, "--model");
  if (document.is_object() && document.contains("axes") && document["axes"].is_object()) {
    for (const auto& [name, model] : document["axes"].items()) {
      refuse_failed_fit(model, "/axes/" + name, arguments);
    }
  } else {
    refuse_failed_fit(document, "", arguments);
  }
  std::vector<Axis> axes;
  try {
    if (document.is_object() && document.contains("axes")) {
      if (document.size() != 1 || !document["axes"].is_object() || document["axes"].empty()) {
        throw ConfigError(
            "/axes: expected {\"axes\": {\"<column>\": <noise model>, ...}} and nothing else");
      }
      for (const auto& [name, model] : document["axes"].items()) {
        axes.push_back({name, noise_model_from_json(model, "/axes/" + name)});
      }
    } else {
      axes.push_back({"value", noise_model_from_json(document)});
    }
  } catch (const ConfigError& error) {
    throw ConfigError(arguments.model_path + ": " + error.what());
  }
  if (!arguments.columns.empty()) {
    if (arguments.columns.size() != axes.size()) {
      throw ConfigError(fmt::format("--column gives {} names for {} axes in {}",
                                    arguments.columns.size(), axes.size(), arguments.model_path));
    }
    for (std::size_t i = 0; i < axes.size(); ++i) axes[i].column = arguments.columns[i];
  }
  // The record must read back: no second time column, no name the CSV would split or break.
  for (const Axis& axis : axes) {
    const std::string& name = axis.column;
    if (name == "t" || name == "t_s" || name == "time" || name == "time_s") {
      throw ConfigError("--column " + name + ": the name of the time column; choose another "
                        "column name");
    }
    if (name.empty() || name.find_first_of(",\"\r\n") != std::string::npos) {
      throw ConfigError("--column '" + name + "': a column name must be non-empty without "
                        "commas, quotes or line breaks; choose another name");
    }
    if (std::count_if(axes.begin(), axes.end(), [&](const Axis& a) { return a.column == name; }) >
        1) {
      throw ConfigError("--column " + name + ": given to two axes; the record would read back "
                        "only one of them: give each axis its own name");
    }
  }
  return axes;
}

// The record's sample count, refused up front when absurd (core/work_limits.hpp).
std::uint64_t checked_sample_count(const NoiseArguments& arguments) {
  if (!(arguments.duration_s > 0.0) || !std::isfinite(arguments.duration_s)) {
    throw ConfigError("--duration must be a finite number of seconds > 0");
  }
  if (!(arguments.rate_hz > 0.0) || !std::isfinite(arguments.rate_hz)) {
    throw ConfigError("--rate must be a finite number of Hz > 0");
  }
  if (arguments.rate_hz > limits::kMaxSimulatedRateHz) {
    throw ConfigError(fmt::format("--rate {:g} Hz is above the limit of {:g} Hz; give a lower "
                                  "--rate (docs/reliability.md, Limits on work)",
                                  arguments.rate_hz, limits::kMaxSimulatedRateHz));
  }
  const double samples = std::round(arguments.duration_s * arguments.rate_hz);
  if (samples > limits::kMaxSimulatedSamples) {
    throw ConfigError(fmt::format(
        "--duration {:g} s at --rate {:g} Hz is {:.3g} samples, above the limit of {:.3g} per "
        "record; shorten --duration or lower --rate, or simulate several records with different "
        "--seed (docs/reliability.md, Limits on work)",
        arguments.duration_s, arguments.rate_hz, samples, limits::kMaxSimulatedSamples));
  }
  if (samples < 2) throw ConfigError("--duration x --rate gives fewer than 2 samples");
  return static_cast<std::uint64_t>(samples);
}

// A model whose numbers overflow a double (parameters near 1e300, a random walk run for ages)
// gives infinities: no record, and a message saying which model and where.
void check_finite(const std::vector<double>& block, std::size_t count, std::uint64_t first,
                  const NoiseArguments& arguments, const Axis& axis) {
  const double per_unit = si_per_unit(axis.model.unit);
  for (std::size_t k = 0; k < count; ++k) {
    // As written: in the model's unit.
    if (!std::isfinite(block[k] / per_unit)) {
      throw ConfigError(fmt::format(
          "{}: the simulated {} is not finite at t = {:g} s (the model's parameters are too "
          "large for a double); use parameters of a physical size",
          arguments.model_path, axis.column, static_cast<double>(first + k) / arguments.rate_hz));
    }
  }
}

void run_simulate_noise(const NoiseArguments& arguments) {
  const std::uint64_t samples = checked_sample_count(arguments);
  const std::vector<Axis> axes = read_axes(arguments);

  std::vector<NoiseGenerator> generators;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    // Axis i uses its own stream, so axes are independent and adding one changes no other.
    const std::uint64_t seed = axes.size() == 1 ? arguments.seed
                                                : derive_stream_seed(arguments.seed, 1000 + i);
    generators.emplace_back(axes[i].model, arguments.rate_hz, seed, arguments.duration_s);
  }
  // Auxiliary channels that aux_sensitivity terms read (temperature), one column each, after
  // the axes; the first term naming a column gives its profile.
  std::vector<AuxSensitivityTerm> aux_channels;
  for (const auto& axis : axes) {
    for (const auto& term : axis.model.terms) {
      const auto* aux = std::get_if<AuxSensitivityTerm>(&term);
      if (aux == nullptr) continue;
      const bool seen = std::any_of(aux_channels.begin(), aux_channels.end(),
                                    [&](const auto& c) { return c.column == aux->column; });
      const bool clashes = std::any_of(axes.begin(), axes.end(),
                                       [&](const Axis& a) { return a.column == aux->column; });
      if (clashes) {
        throw ConfigError(arguments.model_path + ": aux_sensitivity column \"" + aux->column +
                          "\" is also an axis name; rename one of them");
      }
      if (!seen) aux_channels.push_back(*aux);
    }
  }
  PendingFile pending(arguments.out);
  std::ofstream out = pending.open_stream();
  out << 't';
  for (const auto& axis : axes) out << ',' << axis.column;
  for (const auto& aux : aux_channels) out << ',' << aux.column;
  out << '\n';
  constexpr std::size_t kBlock = 1 << 14;
  std::vector<std::vector<double>> blocks(axes.size(), std::vector<double>(kBlock));
  std::string line;
  for (std::uint64_t begin = 0; begin < samples; begin += kBlock) {
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(kBlock, samples - begin));
    for (std::size_t a = 0; a < axes.size(); ++a) {
      generators[a].generate(std::span<double>(blocks[a].data(), count));
      check_finite(blocks[a], count, begin, arguments, axes[a]);
    }
    for (std::size_t k = 0; k < count; ++k) {
      line = fmt::format("{:.10g}", static_cast<double>(begin + k) / arguments.rate_hz);
      for (std::size_t a = 0; a < axes.size(); ++a) {
        fmt::format_to(std::back_inserter(line), ",{:.10g}",
                       blocks[a][k] / si_per_unit(axes[a].model.unit));
      }
      // The channel at the sample interval's midpoint, where the sampler reads it.
      const double mid = (static_cast<double>(begin + k) + 0.5) / arguments.rate_hz;
      for (const auto& aux : aux_channels) {
        fmt::format_to(std::back_inserter(line), ",{:.10g}", aux.profile_at(mid));
      }
      line += '\n';
      out << line;
    }
    if (!out) throw_write_error(arguments.out, errno);
  }
  out.close();
  if (!out) throw_write_error(arguments.out, errno);
  pending.commit();
}

struct ScenarioArguments {
  std::string config_path;
  std::string out;
  std::optional<std::uint64_t> seed;
};

void run_simulate_scenario(const ScenarioArguments& arguments) {
  const ScenarioConfig config = read_scenario_config(arguments.config_path);
  ScenarioOutputOptions options;
  options.out_dir = arguments.out;
  options.seed = arguments.seed.value_or(config.seed);
  options.progress = ::isatty(STDERR_FILENO) != 0;
  options.source = arguments.config_path;
  write_scenario_outputs(config, options);
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  CLI::App* simulate = app.add_subcommand("simulate", "Simulate noise records and MWD scenarios");
  simulate->require_subcommand(1);

  auto noise = std::make_shared<NoiseArguments>();
  CLI::App* noise_command = simulate->add_subcommand("noise", "A noise record from a noise model");
  noise_command->add_option("--model", noise->model_path, "Noise model JSON (or {\"axes\": {...}})")
      ->required();
  noise_command->add_option("--duration", noise->duration_s, "Record length (s)")->required();
  noise_command->add_option("--rate", noise->rate_hz, "Sampling rate (Hz)")->required();
  noise_command->add_option("--seed", noise->seed, "Random seed")
      ->required()
      ->check(whole_number());
  noise_command->add_option("--out", noise->out, "Output CSV: t,<column>...")->required();
  noise_command->add_option("--column", noise->columns,
                            "Column name(s), one per axis (default: value, or the axis names)");
  noise_command->add_flag("--accept-failed", noise->accept_failed,
                          "Simulate a model `stochnav fit` flagged as a failed fit");
  noise_command->callback([noise] { run_simulate_noise(*noise); });

  auto scenario = std::make_shared<ScenarioArguments>();
  CLI::App* scenario_command = simulate->add_subcommand(
      "scenario", "An MWD scenario (vibration table or drilling): imu.csv, truth.csv, aids.csv, "
                  "scenario.json");
  scenario_command->add_option("CONFIG", scenario->config_path, "Scenario JSON")->required();
  scenario_command->add_option("--out", scenario->out, "Output folder (created if missing)")
      ->required();
  scenario_command->add_option("--seed", scenario->seed,
                               "Random seed (default: the configuration's \"seed\")")
      ->check(whole_number());
  scenario_command->callback([scenario] { run_simulate_scenario(*scenario); });
}

}  // namespace stochnav::cli

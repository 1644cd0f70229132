// stochnav allan: Allan-family deviations of a record with Stable32 confidence intervals.

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "allan_plot.hpp"
#include "command_support.hpp"
#include "commands.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/report/gnuplot.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"
#include "stochnav/stats/tau_spacing_names.hpp"

namespace stochnav::cli {
namespace {

struct AllanArguments {
  InputArguments input;
  std::string taus = "octave";
  std::string deviation = "oadev";
  std::string format = "table";
  std::string plot;
  std::string fit;
  std::string output;
  std::string edf = "plausible";
};

/// DESIGN.md's layout ("adev", "adev_lo", "adev_hi" hold the deviation of every kind), plus
/// "deviation" (its name) and the same columns under the deviation's own name ("mtie", ...).
/// MTIE and TIE rms have no noise type: their alpha is null (their edf and bounds, NaN, too).
std::string as_json(const std::vector<DeviationPoint>& points, Deviation kind) {
  const std::string name(deviation_name(kind));
  nlohmann::json out = {{"tau", nlohmann::json::array()},   {"adev", nlohmann::json::array()},
                        {"adev_lo", nlohmann::json::array()}, {"adev_hi", nlohmann::json::array()},
                        {"n", nlohmann::json::array()},     {"edf", nlohmann::json::array()},
                        {"alpha", nlohmann::json::array()}};
  for (const auto& p : points) {
    out["tau"].push_back(p.tau_s);
    out["adev"].push_back(p.deviation);
    out["adev_lo"].push_back(p.lower);
    out["adev_hi"].push_back(p.upper);
    out["n"].push_back(p.terms);
    out["edf"].push_back(p.edf);
    if (has_confidence_interval(kind)) {
      out["alpha"].push_back(p.alpha);
    } else {
      out["alpha"].push_back(nullptr);
    }
  }
  out["deviation"] = name;
  if (name != "adev") {
    out[name] = out["adev"];
    out[name + "_lo"] = out["adev_lo"];
    out[name + "_hi"] = out["adev_hi"];
  }
  return out.dump(2) + "\n";
}

std::string as_csv(const std::vector<DeviationPoint>& points) {
  std::string out = "m,tau,n,alpha,edf,adev_lo,adev,adev_hi\n";
  for (const auto& p : points) {
    out += fmt::format("{},{:.10g},{},{},{:.6g},{:.10g},{:.10g},{:.10g}\n", p.m, p.tau_s, p.terms,
                       p.alpha, p.edf, p.lower, p.deviation, p.upper);
  }
  return out;
}

std::string as_table(const std::vector<DeviationPoint>& points, const Record& record,
                     std::size_t samples, Deviation kind) {
  std::string out =
      fmt::format("# {} of {} [{}], {} samples at {} Hz, unit {}\n", deviation_name(kind),
                  record.source, record.column, samples, record.rate_hz, unit_name(record.unit));
  out += fmt::format("{:>9} {:>12} {:>9} {:>5} {:>10} {:>12} {:>12} {:>12}\n", "m", "tau_s", "n",
                     "alpha", "edf", "lower", "deviation", "upper");
  for (const auto& p : points) {
    out += fmt::format("{:>9} {:>12.5e} {:>9} {:>5} {:>10.4g} {:>12.5e} {:>12.5e} {:>12.5e}\n", p.m,
                       p.tau_s, p.terms, p.alpha, p.edf, p.lower, p.deviation, p.upper);
  }
  return out;
}

void run_allan(const AllanArguments& arguments) {
  const OutputFormat format = parse_format(arguments.format);
  const TauSpacing spacing = parse_tau_spacing(arguments.taus, "--taus");
  const Deviation kind = parse_deviation(arguments.deviation);
  const EdfRule edf_rule = parse_edf_rule(arguments.edf);
  if (!arguments.plot.empty()) check_plot_request(arguments.plot);

  // One array of the data: rate samples are integrated into phase where they were read.
  ReadOptions read_options = arguments.input.to_read_options();
  const auto reading = reading_progress("allan: reading", read_options);
  const PhaseRecord input = read_phase_record(read_options);
  reading->finish();
  const Record& record = input.record;
  const std::span<const double> phase = input.phase();
  const auto m_values = averaging_factors(kind, spacing, phase.size(), record.tau0());
  if (m_values.empty()) {
    throw InputError(record.source + ": " + std::to_string(input.samples) +
                     " samples are too few for any " + std::string(deviation_name(kind)) +
                     " averaging time; use a longer record");
  }
  ProgressTicker computing("allan: " + std::string(deviation_name(kind)), 0,
                           standard_error_is_terminal());
  const auto points =
      compute_deviation(kind, phase, record.tau0(), m_values, kStable32Confidence, edf_rule);
  computing.finish();

  std::string text;
  switch (format) {
    case OutputFormat::kJson: text = as_json(points, kind); break;
    case OutputFormat::kCsv: text = as_csv(points); break;
    case OutputFormat::kTable: text = as_table(points, record, input.samples, kind); break;
  }
  if (!arguments.plot.empty()) {
    plot_allan_deviation(points, record, kind, arguments.fit, arguments.plot);
  }
  write_output(arguments.output, text);
}

}  // namespace

void add_allan_command(CLI::App& app) {
  auto arguments = std::make_shared<AllanArguments>();
  CLI::App* command = app.add_subcommand("allan", "Allan deviation with confidence intervals");
  add_input_options(*command, arguments->input);
  command->add_option("--taus", arguments->taus, "octave, decade, dense or all")
      ->capture_default_str();
  command
      ->add_option("--deviation", arguments->deviation,
                   "oadev, adev, mdev, tdev, hdev, ohdev, totdev, mtotdev, ttotdev, htotdev, "
                   "htotdev_nobias, theo1, theo1_nobias, mtie, tierms")
      ->capture_default_str();
  command
      ->add_option("--edf", arguments->edf,
                   "plausible (smallest EDF over the noise types the identification leaves "
                   "open) or stable32 (the identified type's, as Stable32)")
      ->capture_default_str();
  add_format_option(*command, arguments->format);
  command->add_option("--plot", arguments->plot, "Draw the deviation to FILE.png or FILE.svg");
  command->add_option("--fit", arguments->fit,
                      "Noise model JSON (stochnav fit --format json) drawn over the deviation");
  command->add_option("--output", arguments->output, "Write to FILE instead of standard output");
  command->callback([arguments] { run_allan(*arguments); });
}

}  // namespace stochnav::cli

// stochnav wv: the Haar wavelet variance of a record at dyadic scales with the 95 % interval of
// the R package `wv`: classical (streamed from the file) or robust (--robust).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "command_support.hpp"
#include "commands.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/io/sample_count_bound.hpp"
#include "stochnav/io/sample_reader.hpp"
#include "stochnav/report/gnuplot.hpp"
#include "stochnav/stats/robust_wavelet_variance.hpp"
#include "stochnav/stats/wavelet_variance.hpp"
#include "wv_plot.hpp"

namespace stochnav::cli {
namespace {

struct WvArguments {
  InputArguments input;
  bool robust = false;
  double efficiency = kWvRobustEfficiency;
  std::string format = "table";
  std::string plot;
  std::string fit;
  std::string output;
};

/// A record's description (values left empty), its sample count and its wavelet variance.
struct WvResult {
  Record record;
  std::size_t samples = 0;
  std::vector<WaveletVariancePoint> points;
};

std::string wv_record_label(const Record& record) {
  return record.source + " [" + record.column + "]";
}

/// Rate samples in a record: N for rate data, N - 1 (the differences) for phase data.
void check_wv_record_length(const Record& record, std::size_t samples) {
  if (wavelet_variance_levels(samples) >= 3) return;
  throw InputError(fmt::format(
      "{}: {} rate samples give {} wavelet-variance scale(s); wv needs at least 3 (16 samples or "
      "more); use a longer record",
      wv_record_label(record), samples, std::max(wavelet_variance_levels(samples), 0)));
}

[[noreturn]] void throw_constant_wv_record(const Record& record) {
  throw InputError(wv_record_label(record) +
                   ": the rate is constant (every sample the same), so its wavelet variance is "
                   "zero at every scale; check --column (and --data: rate or phase)");
}

/// The classical estimate, streamed block by block: memory is the estimator's delay lines.
WvResult classical_wv_streamed(const ReadOptions& options) {
  const auto bound = sample_count_bound(options);
  HaarWaveletVarianceAccumulator accumulator(bound ? std::max(wavelet_variance_levels(*bound), 1)
                                                   : 62);
  SampleReader reader(options);
  constexpr std::size_t kBlock = std::size_t{1} << 16;
  std::vector<double> block;
  std::vector<double> differences;
  double previous = 0.0;
  bool started = false;
  while (reader.read_block(block, kBlock) > 0) {
    if (options.kind == DataKind::kPhase) {
      // Rate * tau0 = phase differences; the 1 / tau0^2 is applied to the variances at the end,
      // when the time column has given its final rate.
      differences.clear();
      for (double x : block) {
        if (started) differences.push_back(x - previous);
        previous = x;
        started = true;
      }
      accumulator.push(differences);
    } else {
      accumulator.push(block);
    }
    block.clear();
  }
  WvResult result;
  result.samples = accumulator.samples();
  if (reader.samples_read() == 0) {
    throw InputError(options.path + ": no samples in the file; check the file and --column");
  }
  result.record = describe_record(options, reader);
  check_wv_record_length(result.record, result.samples);
  result.points = accumulator.result(result.record.rate_hz);
  if (options.kind == DataKind::kPhase) {
    const double scale = result.record.rate_hz * result.record.rate_hz;
    for (auto& p : result.points) {
      p.variance *= scale;
      p.lower *= scale;
      p.upper *= scale;
    }
  }
  if (result.points.front().variance == 0.0) throw_constant_wv_record(result.record);
  return result;
}

/// The robust estimate: every level's coefficients at once, so the record is read whole.
WvResult robust_wv_in_memory(const ReadOptions& options, double efficiency) {
  Record record = read_record(options);
  std::vector<double> rate = std::move(record.values);
  record.values.clear();
  if (options.kind == DataKind::kPhase) {
    for (std::size_t i = 0; i + 1 < rate.size(); ++i) {
      rate[i] = (rate[i + 1] - rate[i]) * record.rate_hz;
    }
    rate.pop_back();
  }
  WvResult result;
  result.samples = rate.size();
  check_wv_record_length(record, result.samples);
  if (std::all_of(rate.begin(), rate.end(), [&](double y) { return y == rate.front(); })) {
    throw_constant_wv_record(record);
  }
  result.points = robust_haar_wavelet_variance(rate, record.rate_hz, efficiency);
  for (const auto& p : result.points) {
    if (!std::isfinite(p.variance)) {
      throw InputError(fmt::format(
          "{}: the wavelet coefficients at scale {} samples are all equal (a straight-line "
          "record?), so their robust scale is undefined; drop --robust for the classical estimate",
          wv_record_label(record), p.scale_samples));
    }
  }
  result.record = std::move(record);
  return result;
}

std::string wv_json(const std::vector<WaveletVariancePoint>& points) {
  nlohmann::json out = {{"scale_s", nlohmann::json::array()},
                        {"wv", nlohmann::json::array()},
                        {"wv_lo", nlohmann::json::array()},
                        {"wv_hi", nlohmann::json::array()},
                        {"n", nlohmann::json::array()}};
  for (const auto& p : points) {
    out["scale_s"].push_back(p.scale_s);
    out["wv"].push_back(p.variance);
    out["wv_lo"].push_back(p.lower);
    out["wv_hi"].push_back(p.upper);
    out["n"].push_back(p.coefficients);
  }
  return out.dump(2) + "\n";
}

std::string wv_csv(const std::vector<WaveletVariancePoint>& points) {
  std::string out = "level,scale,scale_s,n,wv_lo,wv,wv_hi\n";
  for (const auto& p : points) {
    out += fmt::format("{},{},{:.10g},{},{:.17g},{:.17g},{:.17g}\n", p.level, p.scale_samples,
                       p.scale_s, p.coefficients, p.lower, p.variance, p.upper);
  }
  return out;
}

std::string wv_table(const WvResult& result, bool robust, double efficiency) {
  const Record& record = result.record;
  std::string out = fmt::format(
      "# Haar wavelet variance ({}) of {}, {} samples at {} Hz, unit ({})^2, 95 % interval\n",
      robust ? fmt::format("robust, efficiency {}", efficiency) : std::string("classical"),
      wv_record_label(record), result.samples, record.rate_hz, unit_name(record.unit));
  out += fmt::format("{:>5} {:>9} {:>12} {:>9} {:>12} {:>12} {:>12}\n", "level", "scale", "scale_s",
                     "n", "lower", "wv", "upper");
  for (const auto& p : result.points) {
    out += fmt::format("{:>5} {:>9} {:>12.5e} {:>9} {:>12.5e} {:>12.5e} {:>12.5e}\n", p.level,
                       p.scale_samples, p.scale_s, p.coefficients, p.lower, p.variance, p.upper);
  }
  return out;
}

void run_wv(const WvArguments& arguments) {
  const OutputFormat format = parse_format(arguments.format);
  if (!arguments.plot.empty()) check_plot_request(arguments.plot);
  const ReadOptions options = arguments.input.to_read_options();
  const WvResult result = arguments.robust ? robust_wv_in_memory(options, arguments.efficiency)
                                           : classical_wv_streamed(options);
  std::string text;
  switch (format) {
    case OutputFormat::kJson:
      text = wv_json(result.points);
      break;
    case OutputFormat::kCsv:
      text = wv_csv(result.points);
      break;
    case OutputFormat::kTable:
      text = wv_table(result, arguments.robust, arguments.efficiency);
      break;
  }
  if (!arguments.plot.empty()) {
    plot_wavelet_variance(result.points, result.record, arguments.robust, arguments.fit,
                          arguments.plot);
  }
  write_output(arguments.output, text);
}

}  // namespace

void add_wv_command(CLI::App& app) {
  auto arguments = std::make_shared<WvArguments>();
  CLI::App* command =
      app.add_subcommand("wv", "Haar wavelet variance at dyadic scales with 95 % intervals");
  add_input_options(*command, arguments->input);
  command->add_flag("--robust", arguments->robust,
                    "Robust estimate (Tukey biweight M-estimate of scale, as the R package wv)");
  command
      ->add_option("--efficiency", arguments->efficiency,
                   "Efficiency of the robust estimate at the Gaussian, in (0, 0.99]")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 0.99));
  add_format_option(*command, arguments->format);
  command->add_option("--plot", arguments->plot,
                      "Draw the wavelet variance to FILE.png or FILE.svg");
  command->add_option(
      "--fit", arguments->fit,
      "Noise model JSON (stochnav fit --format json) drawn over the wavelet variance");
  command->add_option("--output", arguments->output, "Write to FILE instead of standard output");
  command->callback([arguments] { run_wv(*arguments); });
}

}  // namespace stochnav::cli

// stochnav fit: the IEEE 952 noise terms of a record (Ceres), and with --window/--step the same
// fit on every DAVAR window, giving each coefficient as a time series (Zhang et al. 2017, Eq. 7).

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "command_support.hpp"
#include "commands.hpp"
#include "fit_arguments.hpp"
#include "fit_report.hpp"
#include "gmwm_fit_run.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_data.hpp"
#include "stochnav/fit/fit_noise_terms.hpp"
#include "stochnav/fit/fit_option_names.hpp"
#include "stochnav/fit/parameter_control_names.hpp"
#include "stochnav/model/noise_term.hpp"
#include "stochnav/stats/davar.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/edf.hpp"
#include "stochnav/stats/parallel.hpp"
#include "stochnav/stats/phase.hpp"
#include "stochnav/stats/tau_spacing_names.hpp"

namespace stochnav::cli {
namespace {


FitOptions fit_options(const FitArguments& arguments) {
  FitOptions options;
  if (arguments.terms_given) {
    options.terms = parse_fit_terms(split_comma_list(arguments.terms), "--terms");
  }
  const bool steered =
      !arguments.start.empty() || !arguments.fix.empty() || !arguments.bound.empty();
  if (steered && !arguments.terms_given) {
    throw ConfigError(
        "--start/--fix/--bound steer the terms of --terms; name them (e.g. --terms "
        "angle_random_walk,gauss_markov,gauss_markov)");
  }
  options.controls = parse_parameter_controls(options.terms, parse_unit(arguments.input.unit),
                                              arguments.start, arguments.fix, arguments.bound);
  // A given term the data leave on its search bound is dropped (and said so in the report).
  options.drop_terms_at_bound = true;
  options.loss = parse_robust_loss(arguments.loss, "--loss");
  options.criterion = parse_information_criterion(arguments.criterion, "--criterion");
  if (const auto problem = options.validate(); !problem.empty()) throw ConfigError(problem);
  return options;
}

/// The fit of one window: the window's Allan deviations with the EDF its length and the
/// record's noise type give at each tau.
FitResult fit_window(const std::vector<double>& adev_row, const DavarResult& davar,
                     const std::vector<double>& edf, const Record& record,
                     const FitOptions& options) {
  std::vector<double> tau, adev_natural, window_edf;
  for (std::size_t j = 0; j < davar.tau_s.size(); ++j) {
    if (!(adev_row[j] > 0.0)) continue;
    tau.push_back(davar.tau_s[j]);
    adev_natural.push_back(adev_row[j] * si_per_unit(record.unit));
    window_edf.push_back(edf[j]);
  }
  return fit_noise_terms(fit_data_from_adev(tau, adev_natural, window_edf, record.unit,
                                            record.rate_hz),
                         options);
}

/// Options only a GMWM fit takes: exit 2 naming the option rather than ignoring it.
void refuse_gmwm_options(const FitArguments& arguments) {
  const std::pair<bool, const char*> gmwm_only[] = {
      {arguments.robust, "--robust"},
      {!arguments.wv_table.empty(), "--wv-table"},
      {!arguments.candidates.empty(), "--candidates"},
      {arguments.gauss_markov_sampling != "mean", "--gauss-markov-sampling"}};
  for (const auto& [given, name] : gmwm_only) {
    if (given) {
      throw ConfigError(std::string(name) + " is a GMWM option; add --method gmwm");
    }
  }
  if (arguments.input.path.empty()) throw ConfigError("--input is required");
}

// The whole record's OADEV at the spacing's factors and the noise terms fitted to it.
struct WholeRecordFit {
  std::vector<DeviationPoint> points;
  FitResult fit;
};

// The OADEV averaging factors of the whole record's fit; InputError when there are too few.
std::vector<std::size_t> whole_record_factors(std::size_t phase_points, const Record& record,
                                              std::size_t samples, TauSpacing spacing) {
  auto m_values = averaging_factors(Deviation::kOadev, spacing, phase_points, record.tau0());
  if (m_values.size() < 2) {
    throw InputError(record.source + ": too short for a fit (" + std::to_string(samples) +
                     " samples); use a longer record");
  }
  return m_values;
}

WholeRecordFit fit_whole_record(std::span<const double> phase, const Record& record,
                                std::size_t samples, TauSpacing spacing,
                                const FitOptions& options) {
  const auto m_values = whole_record_factors(phase.size(), record, samples, spacing);
  WholeRecordFit result;
  result.points = compute_deviation(Deviation::kOadev, phase, record.tau0(), m_values);
  result.fit = fit_noise_terms(
      fit_data_from_deviations(Deviation::kOadev, result.points, record.unit, record.rate_hz),
      options);
  return result;
}

void run_fit(const FitArguments& arguments) {
  if (arguments.method == "gmwm") {
    run_gmwm_fit(arguments);
    return;
  }
  if (arguments.method != "avar") {
    throw ConfigError("--method '" + arguments.method + "': use avar or gmwm");
  }
  refuse_gmwm_options(arguments);
  const OutputFormat format = parse_format(arguments.format);
  FitOptions options = fit_options(arguments);
  const bool windowed = arguments.window > 0 || arguments.step > 0;
  const DavarOptions davar_options{.window = arguments.window, .step = arguments.step};
  if (windowed) {
    if (const auto problem = davar_options.validate(0); !problem.empty()) throw ConfigError(problem);
  }

  const TauSpacing spacing = parse_tau_spacing(arguments.taus, "--taus", false);
  if (!windowed) {
    // The record integrated into phase where it was read: one array (a 72 M-sample record in
    // 0.6 GB, not 1.1).
    ReadOptions read_options = arguments.input.to_read_options();
    const auto reading = reading_progress("fit: reading", read_options);
    const PhaseRecord input = read_phase_record(read_options);
    reading->finish();
    ProgressTicker fitting("fit: fitting", 0, standard_error_is_terminal());
    const WholeRecordFit whole = fit_whole_record(input.phase(), input.record, input.samples,
                                                  spacing, options);
    fitting.finish();
    // A failed fit is no result a script may take for one: exit 2 naming the term and the
    // reason, unless the user asked for it (flagged in the output).
    if (whole.fit.diagnostics.failed() && !arguments.keep_failed) {
      throw InputError(fmt::format("{}: fit failed: {}; choose other --terms, or give "
                                   "--keep-failed to write the failed fit (flagged)",
                                   input.record.source, whole.fit.diagnostics.failure()));
    }
    write_output(arguments.output, format_fit(whole.fit, input.record, input.samples, format));
    return;
  }

  // One array of the record (item 11 of issue #26): the windows' DAVAR reads the rate
  // samples, which are then integrated into the whole record's phase in place (room for its
  // first point is read in front of them).
  ReadOptions read_options = arguments.input.to_read_options();
  const auto reading = reading_progress("fit: reading", read_options);
  const std::size_t leading = read_options.kind == DataKind::kRate ? 1 : 0;
  Record record = read_record(read_options, leading);
  reading->finish();
  const std::size_t samples = record.values.size() - leading;
  whole_record_factors(record.values.size(), record, samples, spacing);
  if (const auto problem = davar_options.validate(samples); !problem.empty()) {
    throw ConfigError(record.source + ": " + problem);
  }
  const DavarResult davar =
      dynamic_allan_deviation(std::span<const double>(record.values).subspan(leading),
                              record.kind, record.rate_hz, record.start_time_s, davar_options,
                              record.source);
  if (leading > 0) phase_from_rate_in_place(record.values, record.tau0());
  const WholeRecordFit whole_record =
      fit_whole_record(record.values, record, samples, spacing, options);
  const FitResult& whole = whole_record.fit;
  const std::vector<DeviationPoint>& points = whole_record.points;

  // Every window is fitted with the terms chosen on the whole record, so that each coefficient
  // is one continuous time series. The whole record's fit only chooses them: a record that
  // needs windows is one no constant model describes (its chi-square fails), and each window's
  // own fit is checked below.
  // Steered terms keep their order (the controls index them): the windows fit them as given.
  if (!options.controls.empty() && !whole.diagnostics.dropped_terms.empty()) {
    throw InputError(fmt::format(
        "{}: the whole record's fit dropped {}; windows steered by --start/--fix/--bound fit "
        "every term given: remove it from --terms",
        record.source, whole.diagnostics.dropped_terms.front()));
  }
  if (options.controls.empty()) options.terms = whole.diagnostics.chosen_terms;
  // Every window keeps every term, so each coefficient stays one series; a window that leaves
  // a term on its bound is a failed window.
  options.drop_terms_at_bound = false;
  std::vector<double> edf;
  for (std::size_t m : davar.m) {
    int alpha = 0;
    for (const auto& p : points) {
      if (p.m == m) alpha = p.alpha;
    }
    edf.push_back(greenhall_edf({.alpha = alpha, .d = 2, .m = m,
                                 .phase_count = davar.terms.front() + 2 * davar.m.front(),
                                 .overlapping = true}));
  }
  // The windows' fits are independent: spread over the stats threads, each result in its slot.
  std::vector<FitResult> fits(davar.adev.size());
  ProgressTicker fitting("fit: windows", fits.size(), standard_error_is_terminal());
  std::atomic<std::uint64_t>* const fitted = fitting.counter();
  parallel_for(fits.size(), [&](std::size_t k) {
    fits[k] = fit_window(davar.adev[k], davar, edf, record, options);
    if (fitted != nullptr) fitted->fetch_add(1, std::memory_order_relaxed);
  });
  fitting.finish();
  std::size_t failed_windows = 0;
  std::size_t first_failed = 0;
  for (std::size_t k = fits.size(); k-- > 0;) {
    if (fits[k].diagnostics.failed()) {
      ++failed_windows;
      first_failed = k;
    }
  }
  if (failed_windows > 0 && !arguments.keep_failed) {
    throw InputError(fmt::format(
        "{}: fit failed in {} of {} windows, first at t = {:g} s: {}; use longer --window, "
        "fewer --terms, or give --keep-failed to write them (flagged)",
        record.source, failed_windows, fits.size(), davar.time_s[first_failed],
        fits[first_failed].diagnostics.failure()));
  }
  write_output(arguments.output, format_windowed_fit(davar.time_s, fits, record, davar_options,
                                                     format));
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto arguments = std::make_shared<FitArguments>();
  CLI::App* command = app.add_subcommand(
      "fit", "Fit the IEEE 952 noise terms to the Allan variance (--method avar) or by GMWM to "
             "the Haar wavelet variance (--method gmwm)");
  add_input_options(*command, arguments->input);
  // A GMWM fit may read a wavelet-variance table instead (checked in run_fit).
  command->get_option("--input")->required(false);
  command->add_option("--method", arguments->method,
                      "avar (Allan variance, robust log fit) or gmwm (wavelet variance, GMM)")
      ->capture_default_str();
  command->add_flag("--robust", arguments->robust,
                    "gmwm: fit the robust wavelet variance (wv --robust), for records with "
                    "outliers");
  command->add_option("--wv-table", arguments->wv_table,
                      "gmwm: fit a wavelet-variance CSV (scale_s, wv, ci_low/wv_lo, "
                      "ci_high/wv_hi; --column picks a channel, --unit its unit)");
  command->add_option("--candidates", arguments->candidates,
                      "gmwm: models \"a+b;a+b+c\" ranked by WIC (\"ranking\" in the JSON); the "
                      "best is written");
  command->add_option("--gauss-markov-sampling", arguments->gauss_markov_sampling,
                      "gmwm: mean (samples are interval means, as sim/ makes them) or point (a "
                      "discrete AR1, the R gmwm package's)")
      ->capture_default_str();
  command->add_option("--start", arguments->start,
                      "Starting values TERM[#K].PARAM=V,... of --terms, reporting units "
                      "(gauss_markov#2.tau_c=100); both methods");
  command->add_option("--fix", arguments->fix,
                      "Parameters held TERM[#K].PARAM=V,... (gauss_markov#2.tau_c=300), reported "
                      "with sigma 0; both methods");
  command->add_option("--bound", arguments->bound,
                      "Search ranges TERM[#K].PARAM=LOW:HIGH,... (gauss_markov.tau_c=5:500); "
                      "both methods");
  command->add_option("--terms", arguments->terms,
                      "Comma-separated terms (default: chosen by the information criterion)");
  command->add_flag("--keep-failed", arguments->keep_failed,
                    "Write a failed fit (flagged \"failed\" in its JSON) and exit 0 instead of "
                    "exit 2");
  command->add_option("--taus", arguments->taus, "octave, decade or dense")->capture_default_str();
  command->add_option("--loss", arguments->loss, "Robust loss: huber, cauchy or none")
      ->capture_default_str();
  command->add_option("--criterion", arguments->criterion, "Term selection: bic or aic")
      ->capture_default_str();
  command->add_option("--window", arguments->window, "Fit every DAVAR window of N samples")
      ->check(positive_count());
  command->add_option("--step", arguments->step, "Samples between DAVAR windows")
      ->check(positive_count());
  add_format_option(*command, arguments->format);
  command->add_option("--output", arguments->output, "Write to FILE instead of standard output");
  command->callback([arguments, command] {
    arguments->terms_given = command->count("--terms") > 0;
    run_fit(*arguments);
  });
}

}  // namespace stochnav::cli

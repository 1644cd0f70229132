#include "gmwm_fit_run.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "fit_report.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_option_names.hpp"
#include "stochnav/fit/gmwm_fit.hpp"
#include "stochnav/fit/parameter_control_names.hpp"

namespace stochnav::cli {
namespace {

void refuse_avar_options(const FitArguments& arguments) {
  if (arguments.window > 0 || arguments.step > 0) {
    throw ConfigError(
        "--window/--step: windowed fits are Allan-variance fits; drop them or use "
        "--method avar");
  }
  if (arguments.terms_given == !arguments.candidates.empty()) {
    throw ConfigError(
        "--method gmwm: give the model with --terms (e.g. angle_random_walk,"
        "gauss_markov,rate_random_walk) or several with --candidates \"a+b;a+b+c\", "
        "not both");
  }
  if (!arguments.wv_table.empty() && !arguments.input.path.empty()) {
    throw ConfigError("--wv-table and --input: give one of them");
  }
  if (arguments.wv_table.empty() && arguments.input.path.empty()) {
    throw ConfigError(
        "--method gmwm: give the record (--input F) or its wavelet variance "
        "(--wv-table F.csv)");
  }
  if (!arguments.wv_table.empty() && arguments.robust) {
    throw ConfigError(
        "--robust with --wv-table: the table is already computed; compute a robust "
        "one with `stochnav wv --robust --format csv` from the record");
  }
}

/// The wavelet variance of the record, classical or robust, and a description of the record.
GmwmData record_wavelet_variance(const FitArguments& arguments, Record& record) {
  record = read_record(arguments.input.to_read_options());
  std::vector<double> rate = std::move(record.values);
  if (record.kind == DataKind::kPhase) {
    for (std::size_t i = 0; i + 1 < rate.size(); ++i) {
      rate[i] = (rate[i + 1] - rate[i]) * record.rate_hz;
    }
    if (!rate.empty()) rate.pop_back();
  }
  GmwmData data = gmwm_data_from_rate(rate, record.rate_hz, record.unit, arguments.robust,
                                      record.source + " [" + record.column + "]");
  record.values.assign(rate.size(), 0.0);  // only the count is reported
  return data;
}

std::vector<std::vector<TermType>> parse_candidates(const std::string& text) {
  std::vector<std::vector<TermType>> candidates;
  std::string item;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && text[i] != ';') {
      item += text[i] == '+' ? ',' : text[i];
      continue;
    }
    if (!item.empty())
      candidates.push_back(parse_fit_terms(split_comma_list(item), "--candidates"));
    item.clear();
  }
  if (candidates.empty()) {
    throw ConfigError("--candidates: no model named; write \"a+b;a+b+c\" with term names");
  }
  return candidates;
}

}  // namespace

void run_gmwm_fit(const FitArguments& arguments) {
  const OutputFormat format = parse_format(arguments.format);
  refuse_avar_options(arguments);
  GmwmOptions options;
  // A given term the data leave on its search bound is dropped, named in the report (as the
  // Allan fit does); a candidate of --candidates likewise.
  options.drop_terms_at_bound = true;
  options.gauss_markov_sampling =
      parse_gauss_markov_sampling(arguments.gauss_markov_sampling, "--gauss-markov-sampling");
  std::vector<std::vector<TermType>> candidates;
  if (arguments.terms_given) {
    options.terms = parse_fit_terms(split_comma_list(arguments.terms), "--terms");
  } else {
    candidates = parse_candidates(arguments.candidates);
  }
  const Unit unit = parse_unit(arguments.input.unit);
  options.controls = parse_parameter_controls(options.terms, unit, arguments.start, arguments.fix,
                                              arguments.bound);
  if (!candidates.empty() && !options.controls.empty()) {
    throw ConfigError("--start/--fix/--bound apply to one model (--terms), not to --candidates");
  }
  if (const auto problem = options.validate(); !problem.empty() && arguments.terms_given) {
    throw ConfigError(problem);
  }
  Record record;
  GmwmData data;
  if (arguments.wv_table.empty()) {
    data = record_wavelet_variance(arguments, record);
  } else {
    data = read_wavelet_variance_table(arguments.wv_table, arguments.input.column, unit,
                                       arguments.input.rate_hz.value_or(0.0));
    record.source = arguments.wv_table;
    record.column = arguments.input.column.empty() ? "wv" : arguments.input.column;
    record.unit = unit;
    record.rate_hz = data.rate_hz;
  }
  const FitResult fit = candidates.empty() ? fit_gmwm(data, options)
                                           : rank_gmwm_models(data, candidates, options).front();
  if (fit.diagnostics.failed() && !arguments.keep_failed) {
    throw InputError(
        fmt::format("{}: GMWM fit failed: {}; choose other --terms, or give "
                    "--keep-failed to write the failed fit (flagged)",
                    data.source, fit.diagnostics.failure()));
  }
  write_output(arguments.output, format_fit(fit, record, record.values.size(), format));
}

}  // namespace stochnav::cli

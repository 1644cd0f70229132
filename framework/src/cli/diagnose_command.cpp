// stochnav diagnose: where a noise model and a measured record disagree, the missing effect
// named, added and the gap shown shrinking (DESIGN.md, "The discrepancy workflow").
//
// Outputs in --out DIR: report.json (the DESIGN.md contract), report.md, and the plots
// allan_initial.png, allan_step<k>.png and davar.png (when an effect is nonstationary). All
// files are written into a staging folder inside DIR and moved into place only when every one
// of them is complete, so a failure leaves no partial output.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <string_view>
#include <utility>

#include <filesystem>
#include <optional>
#include <random>
#include <string>

#include "command_support.hpp"
#include "commands.hpp"
#include "diagnose_plots.hpp"
#include "diagnose_run.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/core/temporary_files.hpp"
#include "stochnav/diagnose/diagnose.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/diagnose/report_json.hpp"
#include "stochnav/diagnose/report_markdown.hpp"
#include "stochnav/core/work_limits.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/model/reporting_units.hpp"
#include "stochnav/report/gnuplot.hpp"
#include "stochnav/io/json_document.hpp"

namespace stochnav::cli {
namespace {

namespace fs = std::filesystem;

struct DiagnoseArguments {
  InputArguments input;
  bool unit_given = false;
  std::string model_path;
  std::string out_dir;
  DiagnoseOptions options;
  std::string plots = "png";
  std::vector<std::string> aux_columns;      ///< --aux: auxiliary channels of the input
  std::string aux_file;                      ///< --aux-file: with --run, the channels' CSV
  std::string run_dir;                       ///< --run: diagnose a filter run instead
  InnovationAnalysisOptions run_options;     ///< its options
};

NoiseModel read_model(const std::string& path) {
  const nlohmann::json json = read_json_document(path, "--model");
  try {
    return noise_model_from_json(json);
  } catch (const ConfigError& error) {
    throw ConfigError(path + ": " + error.what());
  }
}

// A folder inside `out` that disappears unless its files were moved out.
class StagingFolder final {
 public:
  explicit StagingFolder(const fs::path& out) {
    std::random_device entropy;
    path_ = out / fmt::format(".diagnose-staging-{:08x}", entropy());
    registration_.emplace(path_);
    std::error_code error;
    create_directories_before_cleanup(path_, error);
    if (error) throw fs::filesystem_error("cannot create the staging folder", path_, error);
  }
  ~StagingFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  std::optional<TemporaryPath> registration_;  // removed on SIGINT/SIGTERM too
};

// DiagnoseOptions::validate's reason ("seeds: 1; ...") naming the option a user typed.
std::string with_option_name(const std::string& problem) {
  static const std::array<std::pair<const char*, const char*>, 4> kOptions{{
      {"seeds: ", "--seeds "},
      {"max_iterations: ", "--max-iterations "},
      {"alpha: ", "--alpha "},
      {"windows: ", "--windows "},
  }};
  for (const auto& [field, option] : kOptions) {
    if (problem.starts_with(field)) return option + problem.substr(std::string_view(field).size());
  }
  return problem;
}

// diagnose() with its stages drawn as a bar when standard error is a terminal; an early end of
// the loop completes the bar.
DiagnoseResult diagnose_with_progress(const Record& record, const NoiseModel& model,
                                      DiagnoseOptions options, const std::vector<AuxChannel>& aux) {
  ProgressTicker progress("diagnose", diagnose_stage_count(options.max_iterations),
                          standard_error_is_terminal());
  options.stages_done = progress.counter();
  DiagnoseResult result = diagnose(record, model, options, aux);
  progress.finish();
  return result;
}

// The wavelet-variance findings on the terminal, one line each, when there is something to say.
void print_wavelet_findings(const DiagnoseResult& result, Unit unit) {
  if (const auto& check = result.wavelet_outliers; check && check->contaminated) {
    const auto [low, high] = check->flagged_scale_range_s();
    const auto [excess, at] = check->largest_excess();
    std::string where;
    for (const OutlierSample& sample : check->worst) {
      where += fmt::format("{}{:.2f}", where.empty() ? "" : ", ", sample.time_s);
    }
    fmt::print(
        "  outliers: classical WV exceeds the robust one at scales {:.3g} .. {:.3g} s (by up to "
        "{:.0f} % at {:.3g} s){}; {}\n",
        low, high, 100.0 * excess, at, where.empty() ? "" : "; worst samples at t = " + where + " s",
        check->explained_by_nonstationary ? "the nonstationary stretch found above"
                                          : "use `fit --method gmwm --robust`");
  }
  if (const auto& check = result.short_tau_gauss_markov; check && check->named) {
    const auto& gm = std::get<GaussMarkovTerm>(check->term);
    const Quantity quantity = quantity_of(unit);
    fmt::print(
        "  short-tau gauss_markov (wavelet variance): sigma = {:.4g} {}, tau_c = {:.3g} s{}\n",
        to_reported(quantity, ParameterDimension::kRate, gm.sigma),
        reported_unit_name(quantity, ParameterDimension::kRate), gm.tau_c,
        check->at_lower_end ? " (on the lower end of the range searched: this order or shorter)"
                            : "");
  }
}

void run_diagnose(const DiagnoseArguments& arguments) {
  if (arguments.plots != "png" && arguments.plots != "svg" && arguments.plots != "none") {
    throw ConfigError("--plots '" + arguments.plots + "': use png, svg or none");
  }
  const NoiseModel model = read_model(arguments.model_path);
  ReadOptions read_options = arguments.input.to_read_options();
  if (!arguments.unit_given) read_options.unit = model.unit;
  if (const auto problem = arguments.options.validate(); !problem.empty()) {
    throw ConfigError(with_option_name(problem));
  }
  const fs::path out(arguments.out_dir);
  const std::string extension = "." + arguments.plots;
  const bool plotting = arguments.plots != "none";
  if (plotting) check_plot_request(out / ("allan_initial" + extension));
  const auto reading = reading_progress("diagnose: reading", read_options);
  const Record record = read_record(read_options);
  reading->finish();
  read_options.bytes_read = nullptr;  // the auxiliary channels: read again, not counted
  if (quantity_of(model.unit) != quantity_of(record.unit)) {
    throw ConfigError(arguments.model_path + ": the model is in " + unit_name(model.unit) +
                      " but the record in " + unit_name(record.unit) +
                      "; pass a matching --unit (or leave it out to use the model's)");
  }
  // Auxiliary channels: those asked for, and those the model's aux_sensitivity terms read.
  std::vector<std::string> aux_names = arguments.aux_columns;
  for (const NoiseTerm& term : model.terms) {
    if (const auto* aux = std::get_if<AuxSensitivityTerm>(&term)) aux_names.push_back(aux->column);
  }
  std::vector<AuxChannel> aux;
  for (const std::string& name : aux_names) {
    if (std::any_of(aux.begin(), aux.end(), [&](const AuxChannel& c) { return c.name == name; })) {
      continue;
    }
    ReadOptions aux_options = read_options;
    aux_options.column = name;
    aux_options.kind = DataKind::kRate;
    aux_options.unit = Unit::kPlain;
    aux.push_back({name, read_record(aux_options).values});
  }
  const DiagnoseResult result = diagnose_with_progress(record, model, arguments.options, aux);

  OutputFolder out_folder(out);
  StagingFolder staging(out);
  std::vector<std::string> files;
  DiagnosePlotFiles plots;
  if (plotting) {
    plots.initial = "allan_initial" + extension;
    plot_diagnose_step(result.measured, nullptr, result.initial, "model as given", record,
                       staging.path() / plots.initial);
    files.push_back(plots.initial);
    const ModelAssessment* before = &result.initial;
    for (std::size_t i = 0; i < result.iterations.size(); ++i) {
      const auto& step = result.iterations[i];
      const std::string name = fmt::format("allan_step{}{}", i + 1, extension);
      plot_diagnose_step(result.measured, before, step.after,
                         fmt::format("step {}: + {}", i + 1, term_type_name(step.effect)), record,
                         staging.path() / name);
      plots.steps.push_back(name);
      files.push_back(name);
      before = &step.after;
    }
    const ModelAssessment& last = result.final_assessment();
    const bool nonstationary = find_nonstationary(last.model) != nullptr ||
                               last.gap.stationarity.p_value < arguments.options.alpha;
    if (nonstationary && !result.measured.windows.avar.empty()) {
      plots.davar = "davar" + extension;
      plot_diagnose_davar(record, result.measured, last.gap.stationarity, last.model,
                          staging.path() / plots.davar);
      files.push_back(plots.davar);
    }
  }
  const std::string source = record.source + " [" + record.column + "]";
  write_file_atomically(staging.path() / "report.md",
                        diagnose_report_markdown(result, source, arguments.model_path, plots));
  files.push_back("report.md");
  write_file_atomically(staging.path() / "report.json",
                        diagnose_report_json(result).dump(2) + "\n");
  files.push_back("report.json");
  // Stale plots of an earlier run would contradict this report.
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("allan_step", 0) == 0 || name.rfind("davar.", 0) == 0) {
      fs::remove(entry.path(), error);
    }
  }
  for (const auto& name : files) fs::rename(staging.path() / name, out / name);
  out_folder.keep();

  fmt::print("{}: {} (gap {:.3g} -> {:.3g}, {} step(s)); report in {}\n", source,
             result.consistent ? "consistent" : "not consistent", result.initial.gap.value,
             result.final_assessment().gap.value, result.iterations.size(),
             (out / "report.md").string());
  for (std::size_t i = 0; i < result.iterations.size(); ++i) {
    const auto& step = result.iterations[i];
    std::string flag;  // a term on its search bound is never added silently
    for (const auto& name : step.added_term_at_bound) flag += (flag.empty() ? "" : ", ") + name;
    if (!flag.empty()) flag = "; on its search bound: " + flag;
    fmt::print("  step {}: {} (gap {:.3g} -> {:.3g}{})\n", i + 1, term_type_name(step.effect),
               step.gap_before, step.gap_after, flag);
  }  print_wavelet_findings(result, record.unit);
}

}  // namespace

void add_diagnose_command(CLI::App& app) {
  auto arguments = std::make_shared<DiagnoseArguments>();
  CLI::App* command = app.add_subcommand(
      "diagnose",
      "Find what a noise model misses in a record (--input, --model), name it, add it, show the "
      "gap shrink; or ask a filter run's innovations the same question (--run)");
  add_input_options(*command, arguments->input);
  command->get_option("--input")->required(false);
  command->get_option("--unit")
      ->description("deg/h, deg/s, rad/s, m/s^2, g or plain (default: the model's unit)")
      ->default_str("");
  command->add_option("--model", arguments->model_path, "Noise model JSON (or fit output)");
  command->add_option("--run", arguments->run_dir,
                      "Folder of a `stochnav run`: diagnose its innovations instead of a record");
  command
      ->add_option("--window-s", arguments->run_options.window_s,
                   "--run: window of the innovation level test (s)")
      ->capture_default_str();
  command
      ->add_option("--max-lag", arguments->run_options.max_lag,
                   "--run: lags of the whiteness test")
      ->capture_default_str()
      ->check(whole_number_in(1, 100000));
  command->add_option("--out", arguments->out_dir, "Folder for report.json, report.md and plots")
      ->required();
  command
      ->add_option("--seeds", arguments->options.seeds,
                   "Simulated records per model for the band (0: none)")
      ->capture_default_str()
      ->check(whole_number_in(0, limits::kMaxDiagnoseSeeds));
  command->add_option("--seed", arguments->options.seed, "First simulation seed")
      ->capture_default_str()
      ->check(whole_number());
  command->add_option("--max-iterations", arguments->options.max_iterations, "Most terms to add")
      ->capture_default_str()
      ->check(whole_number_in(0, limits::kMaxDiagnoseIterations));
  command
      ->add_option("--alpha", arguments->options.alpha,
                   "False-alarm probability of the consistency test")
      ->capture_default_str();
  command->add_option("--windows", arguments->options.windows, "Windows of the stationarity test")
      ->capture_default_str()
      ->check(whole_number_in(4, limits::kMaxStationarityWindows));
  command->add_option("--plots", arguments->plots, "png, svg or none")->capture_default_str();
  command
      ->add_option("--aux", arguments->aux_columns,
                   "Auxiliary columns of the input (e.g. temperature_c): test a bias linear in "
                   "each (aux_sensitivity); with --run, columns of RUN_DIR/aids.csv (or --aux-file) "
                   "the innovations may drift with")
      ->delimiter(',');
  command->add_option("--aux-file", arguments->aux_file,
                      "--run: CSV with a time column t holding the --aux columns");
  command->callback([arguments, command] {
    if (!arguments->run_dir.empty()) {
      if (command->count("--input") > 0 || command->count("--model") > 0) {
        throw ConfigError("diagnose: --run diagnoses a filter run; do not also give --input or "
                          "--model");
      }
      arguments->run_options.alpha = arguments->options.alpha;
      run_innovation_diagnosis(arguments->run_dir, arguments->out_dir, arguments->run_options,
                               arguments->plots, arguments->aux_columns, arguments->aux_file);
      return;
    }
    if (command->count("--input") == 0 || command->count("--model") == 0) {
      throw ConfigError("diagnose: give --input F and --model M.json (a record), or --run DIR "
                        "(a filter run)");
    }
    arguments->unit_given = command->count("--unit") > 0;
    run_diagnose(*arguments);
  });
}

}  // namespace stochnav::cli

#include "stochnav/experiment/comparison.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include <boost/math/distributions/chi_squared.hpp>

#include "records/shared_imu_records.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/io/json_numbers.hpp"
#include "stochnav/core/work_limits.hpp"
#include "stochnav/core/progress_bar.hpp"
#include "stochnav/core/temporary_files.hpp"
#include "stochnav/io/json_document.hpp"
#include "stochnav/experiment/parallel_jobs.hpp"
#include "stochnav/experiment/run_consistency.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/plugin/run_config.hpp"
#include "stochnav/plugin/runtime.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"
#include "stochnav/scenario/scenario_writer.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;

// This run's part of OUT, which shards of a sharded run share (experiment/shard_run.hpp): its
// seeds' scenario folders, removed at the end whatever happens (and on SIGINT/SIGTERM); then
// OUT/.scenarios when empty; and, if the run fails, OUT and the parents it had to create, when
// empty. Nothing another process may be writing is removed.
class ComparisonScratch final {
 public:
  explicit ComparisonScratch(const fs::path& out_dir) : scenarios_(out_dir / ".scenarios") {
    std::error_code error;
    for (fs::path missing = out_dir; !missing.empty() && !fs::exists(missing, error);
         missing = missing.parent_path()) {
      created_.push_back(missing);  // innermost first
      if (missing == missing.parent_path()) break;
    }
    // A signal removes the latest registered empty folder first: outermost registered first.
    for (auto it = created_.rbegin(); it != created_.rend(); ++it) {
      registrations_.emplace_back(
          std::make_unique<TemporaryPath>(*it, TemporaryPath::Removal::kIfEmpty));
    }
    registrations_.emplace_back(
        std::make_unique<TemporaryPath>(scenarios_, TemporaryPath::Removal::kIfEmpty));
  }
  ~ComparisonScratch() {
    std::error_code ignored;
    for (const auto& seed : seeds_) fs::remove_all(seed, ignored);
    fs::remove(scenarios_, ignored);  // only when empty: another shard may be using it
    if (!succeeded_) {
      for (const auto& folder : created_) fs::remove(folder, ignored);  // only when empty
    }
  }
  ComparisonScratch(const ComparisonScratch&) = delete;
  ComparisonScratch& operator=(const ComparisonScratch&) = delete;

  void add_seed_folder(const fs::path& folder) {
    seeds_.push_back(folder);
    registrations_.emplace_back(std::make_unique<TemporaryPath>(folder));
  }
  void succeeded() { succeeded_ = true; }

 private:
  fs::path scenarios_;
  std::vector<fs::path> created_;
  std::vector<fs::path> seeds_;
  std::vector<std::unique_ptr<TemporaryPath>> registrations_;
  bool succeeded_ = false;
};

template <typename Error>
[[noreturn]] void rethrow_with_context(const Error& error, const std::string& context) {
  throw Error(context + ": " + error.what());
}

double mean_of(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return values.empty() ? std::nan("") : sum / static_cast<double>(values.size());
}

double std_of(const std::vector<double>& values) {
  if (values.size() < 2) return 0.0;
  const double mean = mean_of(values);
  double sum = 0.0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(values.size() - 1));
}

std::vector<double> per_seed(const VariantResults& variant, std::size_t metric) {
  std::vector<double> values;
  for (const auto& run : variant.runs) values.push_back(run.statistics.max_abs(metric));
  return values;
}

std::vector<double> improvement(const VariantResults& variant, const VariantResults& baseline,
                                std::size_t metric) {
  std::vector<double> values;
  for (std::size_t s = 0; s < variant.runs.size(); ++s) {
    const double base = baseline.runs[s].statistics.max_abs(metric);
    const double mine = variant.runs[s].statistics.max_abs(metric);
    values.push_back(base > 0.0 ? 100.0 * (1.0 - mine / base) : std::nan(""));
  }
  return values;
}

nlohmann::json summary(const std::vector<double>& values) {
  return {{"mean", mean_of(values)}, {"std", std_of(values)}, {"per_seed", values}};
}

const VariantResults& baseline_of(const ComparisonResult& result) {
  for (const auto& variant : result.variants) {
    if (variant.name == result.baseline) return variant;
  }
  return result.variants.front();
}

// Sets each value of `overrides` (JSON pointer -> value) in the scenario document; a pointer
// must name an existing value, so that a typo cannot silently add an ignored key.
void apply_scenario_overrides(const nlohmann::json& overrides, const fs::path& scenario_file,
                              nlohmann::json& scenario) {
  for (const auto& [text, value] : overrides.items()) {
    const nlohmann::json::json_pointer pointer(text);
    if (!scenario.contains(pointer)) {
      throw ConfigError("/data/scenario_overrides: " + scenario_file.string() + " has no value at " +
                        text + "; give the pointer of an existing key of the scenario config");
    }
    scenario[pointer] = value;
  }
}

double json_number(const nlohmann::json& value) {
  return value.is_number() ? value.get<double>() : std::nan("");
}

// [lo, hi] with P(mean of n chi2(dof) samples outside) = 5 %, both tails alike:
// chi2_{0.025}(dof n) / n and chi2_{0.975}(dof n) / n. Null without samples.
nlohmann::json mean_chi_square_bounds(int dof, double samples) {
  if (!(samples > 0.0) || dof < 1) return nullptr;
  const boost::math::chi_squared_distribution<double> sum(dof * samples);
  return {boost::math::quantile(sum, 0.025) / samples,
          boost::math::quantile(sum, 0.975) / samples};
}

// Sums of a run's consistency: NEES, the share of epochs inside 3-sigma per metric (as counts
// weighted by the run's NEES samples, which are its scored epochs), NIS per aid.
struct ConsistencySums {
  double nees_sum = 0.0;
  double nees_samples = 0.0;
  std::array<double, kErrorMetricCount> inside_weighted{};
  std::array<double, kErrorMetricCount> inside_weight{};
  struct Aid {
    std::string type;
    int dof = 0;
    double nis_sum = 0.0;
    double accepted = 0.0;
    double attempts = 0.0;
  };
  std::vector<Aid> aids;

  void add(const NavigationRunResult& run) {
    const nlohmann::json& c = run.consistency;
    if (c.is_object()) {
      const double samples = c.value("nees_samples", 0.0);
      const double mean = json_number(c.value("nees_mean", nlohmann::json()));
      if (samples > 0.0 && std::isfinite(mean)) {
        nees_sum += mean * samples;
        nees_samples += samples;
      }
      const double weight = samples > 0.0 ? samples : 1.0;
      for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
        const double share = json_number(c["inside_3sigma"].value(
            std::string(kErrorMetricNames[m]), nlohmann::json()));
        if (!std::isfinite(share)) continue;
        inside_weighted[m] += share * weight;
        inside_weight[m] += weight;
      }
    }
    if (!run.aids.is_array()) return;
    if (aids.empty()) {
      for (const auto& aid : run.aids) aids.push_back({aid.value("type", ""), aid.value("dof", 0)});
    }
    for (std::size_t i = 0; i < aids.size() && i < run.aids.size(); ++i) {
      const auto& aid = run.aids[i];
      const double attempts = aid.value("attempts", 0.0);
      const double accepted =
          std::round(attempts * (1.0 - aid.value("rejected_share", 0.0)));
      const double nis = json_number(aid.value("nis_mean", nlohmann::json()));
      aids[i].attempts += attempts;
      if (accepted > 0.0 && std::isfinite(nis)) {
        aids[i].nis_sum += nis * accepted;
        aids[i].accepted += accepted;
      }
    }
  }

  double nees_mean() const { return nees_samples > 0.0 ? nees_sum / nees_samples : std::nan(""); }
  double inside(std::size_t m) const {
    return inside_weight[m] > 0.0 ? inside_weighted[m] / inside_weight[m] : std::nan("");
  }

  // The worst reason the filter is optimistic, or "" (consistent, or without truth).
  std::string optimism() const {
    std::string reason;
    double worst = kConsistentShare;
    for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
      const double share = inside(m);
      if (std::isfinite(share) && share < worst) {
        worst = share;
        reason = fmt::format("{} inside 3-sigma {:.0f} %", kErrorMetricNames[m], 100.0 * share);
      }
    }
    const nlohmann::json bounds = mean_chi_square_bounds(9, nees_samples);
    if (bounds.is_array() && nees_mean() > bounds[1].get<double>()) {
      reason += fmt::format("{}NEES {:.3g} > {:.3g}", reason.empty() ? "" : ", ", nees_mean(),
                            bounds[1].get<double>());
    }
    return reason;
  }

  nlohmann::json json() const {
    if (nees_samples == 0.0 && inside_weight[0] == 0.0 && aids.empty()) return nullptr;
    nlohmann::json inside_json = nlohmann::json::object();
    for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
      inside_json[std::string(kErrorMetricNames[m])] = number_or_null(inside(m));
    }
    nlohmann::json aids_json = nlohmann::json::array();
    for (const Aid& aid : aids) {
      aids_json.push_back(
          {{"type", aid.type},
           {"dof", aid.dof},
           {"attempts", aid.attempts},
           {"nis_mean", number_or_null(aid.accepted > 0.0 ? aid.nis_sum / aid.accepted
                                                           : std::nan(""))},
           {"nis_bounds", mean_chi_square_bounds(aid.dof, aid.accepted)}});
    }
    const std::string reason = optimism();
    return {{"nees_mean", number_or_null(nees_mean())},
            {"nees_dof", 9},
            {"nees_samples", nees_samples},
            {"nees_bounds", mean_chi_square_bounds(9, nees_samples)},
            {"inside_3sigma", inside_json},
            {"aids", aids_json},
            {"optimistic", !reason.empty()},
            {"optimistic_reason", reason}};
  }
};

ConsistencySums consistency_of(const VariantResults& variant) {
  ConsistencySums sums;
  for (const auto& run : variant.runs) sums.add(run);
  return sums;
}

// A white-noise calibration record (2^16 samples at 100 Hz, 655 s): stands in for the real record when
// a fitter is run only to check its params.
plugin::CalibrationRecord probe_record(plugin::SensorGroup group) {
  plugin::CalibrationRecord record;
  record.group = group;
  record.rate_hz = 100.0;
  record.source = "(params check)";
  std::uint64_t state = 12345;
  for (auto& axis : record.axes) {
    axis.resize(1 << 16);
    for (double& value : axis) {  // sum of uniforms: roughly Gaussian, unit variance
      double sum = 0.0;
      for (int k = 0; k < 12; ++k) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        sum += static_cast<double>(state >> 11) * 0x1.0p-53;
      }
      value = 1e-5 * (sum - 6.0);
    }
  }
  return record;
}

}  // namespace

void validate_variants(const ExperimentConfig& config) {
  const plugin::PluginRegistry registry(plugin::default_search_path(config.config_dir));
  for (std::size_t v = 0; v < config.variants.size(); ++v) {
    const auto& variant = config.variants[v];
    const std::string context =
        fmt::format("{}: variant '{}' (/variants/{})", config.file.string(), variant.name, v);
    try {
      // The data section aside, as experiment_config_from_json checks the variants.
      const plugin::RunConfig run =
          plugin::parse_run_config(variant_run_document(variant, nullptr), config.config_dir,
                                   plugin::DataConfig{.imu = fs::absolute(config.file)});
      for (const auto* noise : {&run.noise.gyro, &run.noise.accel}) {
        const auto group =
            noise == &run.noise.gyro ? plugin::SensorGroup::kGyro : plugin::SensorGroup::kAccel;
        const auto& descriptor =
            registry.find(plugin::PluginKind::kNoiseModel, noise->type, noise->type_pointer());
        if (noise->fit && !descriptor.can_fit) {
          throw ConfigError(noise->pointer + "/fit: noise plugin '" + noise->type +
                            "' cannot fit its model from data; remove \"fit\" and give "
                            "\"params\"");
        }
        plugin::NoiseModelContext model_context;
        model_context.group = group;
        model_context.imu_rate_hz = 100.0;
        model_context.params_pointer = noise->options_pointer();
        model_context.config_dir = config.config_dir;
        // The seeds' scenario folders do not exist yet: a model reading its scenario (the
        // oracle) says its data are missing, which is not a params error.
        model_context.scenario_dir = run.data.scenario_dir.empty()
                                         ? config.config_dir / ".scenario-not-simulated-yet"
                                         : run.data.scenario_dir;
        // Params (and fit options) are checked by the plugin itself; an InputError here only
        // says the data are not there yet (a fit to the probe record).
        try {
          if (noise->fit) {
            registry.fit_noise_model(noise->type, probe_record(group), noise->options(),
                                     model_context, noise->type_pointer());
          } else {
            registry.create_noise_model(noise->type, noise->params, model_context,
                                        noise->type_pointer());
          }
        } catch (const InputError&) {
        } catch (const MissingDataError&) {
        }
      }
      // Aids are built on empty aid data: their params are checked by the plugin before it asks
      // for its columns, and a missing column only says the data are not there yet.
      const plugin::AidData no_data;
      plugin::AidContext aid_context;
      aid_context.data = &no_data;
      aid_context.config_dir = config.config_dir;
      for (const auto& aid : run.aids) {
        aid_context.params_pointer = aid.params_pointer();
        try {
          registry.create_aid(aid.type, aid.params, aid_context, aid.type_pointer());
        } catch (const MissingDataError&) {
        }
      }
    } catch (const ConfigError& error) {
      rethrow_with_context(error, context);
    }
  }
}

void check_work_limits(const ExperimentConfig& config) {
  if (config.seeds.size() > limits::kMaxCompareSeeds) {
    throw ConfigError(fmt::format("{}: {} seeds, above the limit of {} per comparison; use fewer "
                                  "seeds (docs/reliability.md, Limits on work)",
                                  config.file.string(), config.seeds.size(),
                                  limits::kMaxCompareSeeds));
  }
  const std::uint64_t runs = config.seeds.size() * config.variants.size();
  if (runs > limits::kMaxCompareRuns) {
    throw ConfigError(fmt::format("{}: {} variants x {} seeds = {} filter runs, above the limit "
                                  "of {} per comparison; use fewer seeds or variants "
                                  "(docs/reliability.md, Limits on work)",
                                  config.file.string(), config.variants.size(),
                                  config.seeds.size(), runs, limits::kMaxCompareRuns));
  }
  std::set<std::uint64_t> distinct(config.seeds.begin(), config.seeds.end());
  if (distinct.size() != config.seeds.size()) {
    throw ConfigError(config.file.string() + ": a seed is given twice; give distinct seeds");
  }
}

ComparisonResult run_comparison(const ExperimentConfig& config, const fs::path& out_dir_given,
                                bool progress_bar) {
  const auto start = std::chrono::steady_clock::now();
  // Absolute: the seeds' folders are handed to run configs that resolve relative paths
  // against the experiment's folder, not the working directory.
  const fs::path out_dir = fs::absolute(out_dir_given);
  check_work_limits(config);
  validate_variants(config);
  const unsigned threads =
      config.threads > 0 ? config.threads : std::max(1u, std::thread::hardware_concurrency());
  const std::size_t seed_count = config.seeds.size();
  const std::size_t job_count = seed_count * config.variants.size();
  ProgressBar progress("compare", (config.scenario_config ? seed_count : 0) + job_count,
                       progress_bar);
  std::atomic<std::uint64_t> done{0};

  // 1. The data of every seed: simulated folders, or the fixed data section.
  std::vector<nlohmann::json> data(seed_count, config.fixed_data);
  const fs::path scenarios_dir = out_dir / ".scenarios";
  ComparisonScratch scratch(out_dir);
  if (config.scenario_config) {
    nlohmann::json scenario_json =
        read_json_document(*config.scenario_config, "the experiment's data/scenario_config");
    apply_scenario_overrides(config.scenario_overrides, *config.scenario_config, scenario_json);
    for (const auto& [text, value] : config.scenario_sweep_values.items()) {
      try {
        scenario_json[nlohmann::json::json_pointer(text)] = value;
      } catch (const nlohmann::json::exception& error) {
        throw ConfigError(config.file.string() + ": /sweep/set: cannot set /scenario" + text +
                          " (" + error.what() + ")");
      }
    }
    ScenarioConfig scenario;
    try {
      scenario = scenario_config_from_json(scenario_json, config.scenario_config->string());
    } catch (const ConfigError& error) {
      rethrow_with_context(error, config.scenario_config->string());
    }
    for (std::size_t s = 0; s < seed_count; ++s) {
      const fs::path seed_dir = scenarios_dir / fmt::format("seed_{}", config.seeds[s]);
      scratch.add_seed_folder(seed_dir);
      data[s] = {{"scenario", seed_dir.string()}};
    }
    run_parallel(seed_count, threads, progress, done, [&](std::size_t s) {
      write_scenario_outputs(scenario, {.out_dir = data[s]["scenario"].get<std::string>(),
                                        .seed = config.seeds[s],
                                        .source = config.scenario_config->string()});
    });
  }

  // 2. Every variant on every seed.
  ComparisonResult result;
  result.baseline = config.baseline;
  result.seeds = config.seeds;
  result.pairs = config.pairs;
  for (const auto& variant : config.variants) {
    result.variants.push_back({variant.name, variant.gyro_plugin, {}});
    result.variants.back().runs.resize(seed_count);
  }
  SharedImuRecords imu_records(seed_count, config.variants.size());
  // Every plugin library is loaded and initialised here, once, before the workers start, and
  // stays loaded until the last job has ended: a job's own registry then finds it loaded. Without
  // this the jobs loaded the libraries concurrently (each job's registry, while no other job held
  // them), one job running a library's static initialisers while another used its globals, the
  // two ordered only by the dynamic loader's internal lock, which the thread sanitizer cannot
  // see (docs/reliability.md, "Thread sanitizer").
  const plugin::PluginRegistry loaded_plugins(plugin::default_search_path(config.config_dir));
  run_parallel(job_count, threads, progress, done, [&](std::size_t job) {
    const std::size_t v = job / seed_count;
    const std::size_t s = job % seed_count;
    const std::string context =
        fmt::format("{}: variant '{}', seed {}", config.file.string(), config.variants[v].name,
                    config.seeds[s]);
    try {
      const plugin::RunConfig run = plugin::parse_run_config(
          variant_run_document(config.variants[v], data[s]), config.config_dir);
      const SharedImuRecords::Lease imu = imu_records.lease(s, run.data.imu);
      result.variants[v].runs[s] = run_navigation(run, {.imu_record = imu.record()});
    } catch (const ConfigError& error) {
      rethrow_with_context(error, context);
    } catch (const InputError& error) {
      rethrow_with_context(error, context);
    }
  });
  progress.finish(done);
  scratch.succeeded();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

double sign_test_p_value(std::size_t wins, std::size_t losses) {
  const std::size_t n = wins + losses;
  if (n == 0) return 1.0;
  // P(X <= k) = sum_{i <= k} C(n, i) / 2^n, the binomial coefficients built up exactly (in
  // double, exact while they stay below 2^53).
  const auto cdf = [n](std::size_t k) {
    double sum = 0.0;
    double coefficient = 1.0;
    for (std::size_t i = 0; i <= k; ++i) {
      sum += coefficient;
      coefficient = coefficient * static_cast<double>(n - i) / static_cast<double>(i + 1);
    }
    return std::ldexp(sum, -static_cast<int>(n));
  };
  const double lower = cdf(wins);
  const double upper = wins == 0 ? 1.0 : 1.0 - cdf(wins - 1);
  return std::min(1.0, 2.0 * std::min(lower, upper));
}

nlohmann::json pair_json(const ComparisonResult& result, const std::string& a,
                         const std::string& b) {
  const VariantResults* first = nullptr;
  const VariantResults* second = nullptr;
  for (const auto& variant : result.variants) {
    if (variant.name == a) first = &variant;
    if (variant.name == b) second = &variant;
  }
  if (first == nullptr || second == nullptr) {
    throw ConfigError("pairs: [" + a + ", " + b + "] names a variant that did not run");
  }
  nlohmann::json metrics = nlohmann::json::object();
  for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
    const auto mine = per_seed(*first, m);
    const auto theirs = per_seed(*second, m);
    std::vector<double> diff;
    std::size_t a_wins = 0, b_wins = 0, ties = 0;
    for (std::size_t s = 0; s < mine.size() && s < theirs.size(); ++s) {
      diff.push_back(mine[s] - theirs[s]);
      if (!std::isfinite(diff.back()) || diff.back() == 0.0) {
        ++ties;
      } else if (diff.back() < 0.0) {
        ++a_wins;
      } else {
        ++b_wins;
      }
    }
    metrics[std::string(kErrorMetricNames[m])] = {
        {"mean_diff", number_or_null(mean_of(diff))},
        {"std_diff", number_or_null(std_of(diff))},
        {"per_seed_diff", diff},
        {"a_wins", a_wins},
        {"b_wins", b_wins},
        {"ties", ties},
        {"sign_test_p", sign_test_p_value(a_wins, b_wins)}};
  }
  return {{"a", a}, {"b", b}, {"metrics", metrics}};
}

nlohmann::json variant_consistency(const ComparisonResult& result, std::size_t index) {
  return consistency_of(result.variants.at(index)).json();
}

nlohmann::json comparison_json(const ComparisonResult& result) {
  const VariantResults& baseline = baseline_of(result);
  nlohmann::json variants = nlohmann::json::array();
  for (const auto& variant : result.variants) {
    nlohmann::json metrics, improvements;
    for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
      const std::string name(kErrorMetricNames[m]);
      metrics[name] = summary(per_seed(variant, m));
      improvements[name] = summary(improvement(variant, baseline, m));
    }
    bool healthy = true;
    for (const auto& run : variant.runs) healthy &= run.health.ok();
    nlohmann::json fitted = nlohmann::json::array();
    nlohmann::json per_seed_consistency = nlohmann::json::array();
    for (const auto& run : variant.runs) {
      fitted.push_back({{"gyro", run.fitted.value("gyro", nlohmann::json())},
                        {"accel", run.fitted.value("accel", nlohmann::json())},
                        {"fit_quality", run.fit_quality}});
      ConsistencySums one;
      one.add(run);
      per_seed_consistency.push_back(one.json());
    }
    nlohmann::json consistency = consistency_of(variant).json();
    if (consistency.is_object()) consistency["per_seed"] = per_seed_consistency;
    variants.push_back({{"name", variant.name},
                        {"noise_model", variant.noise_model},
                        {"metrics", metrics},
                        {"improvement_pct", improvements},
                        {"consistency", consistency},
                        {"fitted", fitted},
                        {"filter_health_ok", healthy}});
  }
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& [a, b] : result.pairs) pairs.push_back(pair_json(result, a, b));
  return {{"baseline", result.baseline},
          {"seeds", result.seeds},
          {"wall_seconds", result.wall_seconds},
          {"variants", variants},
          {"pairs", pairs}};
}

std::string comparison_table(const ComparisonResult& result, const ExperimentConfig& config) {
  const VariantResults& baseline = baseline_of(result);
  std::string table = fmt::format("# {}\n\n", config.file.filename().string());
  if (!config.description.empty()) table += config.description + "\n\n";
  table += fmt::format(
      "Maximum absolute error of each run, mean +/- std over {} seed(s); in brackets the "
      "improvement over the baseline `{}` (100 (1 - variant / baseline) per seed, mean +/- std)."
      "\n\n| metric |",
      result.seeds.size(), result.baseline);
  for (const auto& variant : result.variants) {
    table += fmt::format(" {}{} |", variant.name,
                         consistency_of(variant).optimism().empty() ? "" : " (OPTIMISTIC)");
  }
  table += "\n|---|";
  for (std::size_t i = 0; i < result.variants.size(); ++i) table += "---|";
  table += '\n';
  for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
    table += fmt::format("| {} |", kErrorMetricNames[m]);
    for (const auto& variant : result.variants) {
      const auto values = per_seed(variant, m);
      table += fmt::format(" {:.4g} +/- {:.2g}", mean_of(values), std_of(values));
      if (&variant != &baseline) {
        const auto gain = improvement(variant, baseline, m);
        table += fmt::format(" ({:+.0f} +/- {:.0f} %)", mean_of(gain), std_of(gain));
      }
      table += " |";
    }
    table += '\n';
  }
  table +=
      "\nConsistency over all scored epochs of all seeds: share of epochs inside 3-sigma (worst "
      "metric), mean NEES of the 9 position/velocity/attitude error states with its two-sided "
      "95 % bounds chi2_{0.025, 0.975}(9 N) / N (N epochs x seeds), mean NIS per aid with its "
      "bounds. OPTIMISTIC: a metric inside 3-sigma on fewer than 95 % of the epochs, or the NEES "
      "above its upper bound.\n\n| variant | worst inside 3-sigma | NEES mean [bounds] | NIS "
      "mean per aid [bounds] | verdict |\n|---|---|---|---|---|\n";
  for (const auto& variant : result.variants) {
    const ConsistencySums sums = consistency_of(variant);
    const nlohmann::json json = sums.json();
    if (!json.is_object()) {
      table += fmt::format("| {} | - | - | - | no truth |\n", variant.name);
      continue;
    }
    std::size_t worst = 0;
    for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
      if (std::isfinite(sums.inside(m)) &&
          !(sums.inside(m) >= sums.inside(worst))) {  // also replaces a NaN worst
        worst = m;
      }
    }
    const auto bounds = json["nees_bounds"];
    std::string nis;
    for (const auto& aid : json["aids"]) {
      nis += fmt::format("{}{}: {:.3g}", nis.empty() ? "" : "; ", aid["type"].get<std::string>(),
                         json_number(aid["nis_mean"]));
      if (aid["nis_bounds"].is_array()) {
        nis += fmt::format(" [{:.3g}, {:.3g}]", aid["nis_bounds"][0].get<double>(),
                           aid["nis_bounds"][1].get<double>());
      }
    }
    const std::string reason = sums.optimism();
    table += fmt::format(
        "| {} | {} {:.1f} % | {:.3g} [{}] | {} | {} |\n", variant.name, kErrorMetricNames[worst],
        100.0 * sums.inside(worst), sums.nees_mean(),
        bounds.is_array() ? fmt::format("{:.3g}, {:.3g}", bounds[0].get<double>(),
                                        bounds[1].get<double>())
                          : std::string("-"),
        nis.empty() ? "-" : nis, reason.empty() ? "ok" : "**OPTIMISTIC** (" + reason + ")");
  }
  if (!result.pairs.empty()) {
    table += fmt::format(
        "\nPaired comparisons over the {} seed(s): per metric the mean +/- std of the per-seed "
        "difference A - B of the maximum absolute error, the seeds A wins (smaller error) of "
        "those not tied, and the two-sided exact sign-test p-value.\n\n| metric |",
        result.seeds.size());
    for (const auto& [a, b] : result.pairs) table += fmt::format(" {} - {} |", a, b);
    table += "\n|---|";
    for (std::size_t i = 0; i < result.pairs.size(); ++i) table += "---|";
    table += '\n';
    std::vector<nlohmann::json> pairs;
    for (const auto& [a, b] : result.pairs) pairs.push_back(pair_json(result, a, b));
    for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
      const std::string name(kErrorMetricNames[m]);
      table += fmt::format("| {} |", name);
      for (const auto& pair : pairs) {
        const auto& p = pair["metrics"][name];
        const std::size_t decided = p["a_wins"].get<std::size_t>() + p["b_wins"].get<std::size_t>();
        table += fmt::format(" {:.3g} +/- {:.2g}, A wins {}/{}, p = {:.3g} |",
                             json_number(p["mean_diff"]), json_number(p["std_diff"]),
                             p["a_wins"].get<std::size_t>(), decided,
                             p["sign_test_p"].get<double>());
      }
      table += '\n';
    }
  }
  table += "\nNoise model (gyro plugin) of each variant:";
  for (const auto& variant : result.variants) {
    bool healthy = true;
    for (const auto& run : variant.runs) healthy &= run.health.ok();
    table += fmt::format(" {} = `{}`{};", variant.name, variant.noise_model,
                         healthy ? "" : " (filter health trouble)");
  }
  table.back() = '\n';
  return table;
}

}  // namespace stochnav

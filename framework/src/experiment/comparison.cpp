#include "stochnav/experiment/comparison.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <functional>
#include <mutex>
#include <thread>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/progress_bar.hpp"
#include "stochnav/plugin/run_config.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"
#include "stochnav/scenario/scenario_writer.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;

// Runs jobs 0..count-1 on `threads` workers; rethrows the first failure after all stopped.
void run_parallel(std::size_t count, unsigned threads, ProgressBar& progress,
                  std::atomic<std::uint64_t>& done, const std::function<void(std::size_t)>& job) {
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_failure;
  std::mutex failure_mutex;
  const auto worker = [&] {
    for (std::size_t i = next++; i < count && !failed; i = next++) {
      try {
        job(i);
      } catch (...) {
        const std::lock_guard lock(failure_mutex);
        if (!first_failure) first_failure = std::current_exception();
        failed = true;
      }
      ++done;
      ++finished;
    }
  };
  std::vector<std::thread> pool;
  const unsigned workers = std::max(1u, std::min<unsigned>(threads, static_cast<unsigned>(count)));
  for (unsigned t = 1; t < workers; ++t) pool.emplace_back(worker);
  // A drawer thread keeps the progress up to date until the last job has finished (the last
  // jobs can run for a long time after the last one started).
  std::thread drawer([&] {
    while (finished < count && !failed) {
      progress.show(done);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  worker();
  for (auto& thread : pool) thread.join();
  drawer.join();
  if (first_failure) std::rethrow_exception(first_failure);
}

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

}  // namespace

ComparisonResult run_comparison(const ExperimentConfig& config, const fs::path& out_dir,
                                bool progress_bar) {
  const auto start = std::chrono::steady_clock::now();
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
  if (config.scenario_config) {
    std::ifstream in(*config.scenario_config);
    nlohmann::json scenario_json;
    try {
      scenario_json = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& error) {
      throw InputError(config.scenario_config->string() + ": not valid JSON (" + error.what() +
                       ")");
    }
    apply_scenario_overrides(config.scenario_overrides, *config.scenario_config, scenario_json);
    ScenarioConfig scenario;
    try {
      scenario = scenario_config_from_json(scenario_json, config.scenario_config->string());
    } catch (const ConfigError& error) {
      rethrow_with_context(error, config.scenario_config->string());
    }
    for (std::size_t s = 0; s < seed_count; ++s) {
      data[s] = {{"scenario", (scenarios_dir / fmt::format("seed_{}", config.seeds[s])).string()}};
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
  for (const auto& variant : config.variants) {
    result.variants.push_back({variant.name, variant.gyro_plugin, {}});
    result.variants.back().runs.resize(seed_count);
  }
  run_parallel(job_count, threads, progress, done, [&](std::size_t job) {
    const std::size_t v = job / seed_count;
    const std::size_t s = job % seed_count;
    const std::string context =
        fmt::format("{}: variant '{}', seed {}", config.file.string(), config.variants[v].name,
                    config.seeds[s]);
    try {
      const plugin::RunConfig run = plugin::parse_run_config(
          variant_run_document(config.variants[v], data[s]), config.config_dir);
      result.variants[v].runs[s] = run_navigation(run, NavigationRunOptions{});
    } catch (const ConfigError& error) {
      rethrow_with_context(error, context);
    } catch (const InputError& error) {
      rethrow_with_context(error, context);
    }
  });
  progress.finish(done);
  std::error_code ignored;
  fs::remove_all(scenarios_dir, ignored);
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
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
    variants.push_back({{"name", variant.name},
                        {"noise_model", variant.noise_model},
                        {"metrics", metrics},
                        {"improvement_pct", improvements},
                        {"filter_health_ok", healthy}});
  }
  return {{"baseline", result.baseline},
          {"seeds", result.seeds},
          {"wall_seconds", result.wall_seconds},
          {"variants", variants}};
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
  for (const auto& variant : result.variants) table += fmt::format(" {} |", variant.name);
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

#pragma once
// `stochnav compare`: every variant of an experiment on every seed, in parallel on all cores,
// then the statistics of each error metric (the maximum absolute error of each run, the paper's
// Table 3 measure) over the seeds, and the improvement of each variant over the baseline.
//
// Files in out_dir (written atomically; a failed experiment leaves none):
//   results.json  {"baseline": NAME, "seeds": [...], "variants": [{"name": NAME,
//                  "noise_model": TYPE, "metrics": {METRIC: {"mean": x, "std": y,
//                  "per_seed": [...]}}, "improvement_pct": {METRIC: {"mean", "std",
//                  "per_seed"}}, "filter_health_ok": bool}]}
//                 METRIC as metrics.json of `stochnav run`; std is the sample standard
//                 deviation over seeds (0 for one seed); improvement 100 (1 - variant/baseline)
//                 per seed.
//   table.md      the paper's Table 3 in shape: each metric, each variant (mean +/- std), and
//                 the improvement over the baseline (mean +/- std %).
//   metrics.png   each metric per variant (mean and std over seeds).
//   errors_<variant>.png   errors over time with 3-sigma bounds, first seed.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "stochnav/experiment/experiment_config.hpp"
#include "stochnav/experiment/navigation_run.hpp"

namespace stochnav {

struct VariantResults {
  std::string name;
  std::string noise_model;
  std::vector<NavigationRunResult> runs;  ///< one per seed, in ExperimentConfig::seeds order
};

struct ComparisonResult {
  std::string baseline;
  std::vector<std::uint64_t> seeds;
  std::vector<VariantResults> variants;
  double wall_seconds = 0.0;
};

/// Runs the experiment. Simulated seeds are generated under out_dir/.scenarios (removed at the
/// end). Throws ConfigError / InputError (the first failure of any job, naming the variant and
/// seed).
ComparisonResult run_comparison(const ExperimentConfig& config,
                                const std::filesystem::path& out_dir, bool progress);

/// results.json as described above.
nlohmann::json comparison_json(const ComparisonResult& result);
/// table.md as described above.
std::string comparison_table(const ComparisonResult& result, const ExperimentConfig& config);

/// Writes results.json, table.md and the plots (plots skipped when gnuplot is missing).
void write_comparison(const ComparisonResult& result, const ExperimentConfig& config,
                      const std::filesystem::path& out_dir);

}  // namespace stochnav

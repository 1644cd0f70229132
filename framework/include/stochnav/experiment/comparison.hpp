#pragma once
// `stochnav compare`: every variant of an experiment on every seed, in parallel on all cores,
// then the statistics of each error metric (the maximum absolute error of each run, the paper's
// Table 3 measure) over the seeds, and the improvement of each variant over the baseline.
//
// Files in out_dir (written atomically; a failed experiment leaves none):
//   results.json  {"baseline": NAME, "seeds": [...], "variants": [{"name": NAME,
//                  "noise_model": TYPE, "metrics": {METRIC: {"mean": x, "std": y,
//                  "per_seed": [...]}}, "improvement_pct": {METRIC: {"mean", "std",
//                  "per_seed"}}, "consistency": {...} | null, "fitted": [...],
//                  "filter_health_ok": bool}], "pairs": [...]}
//                 METRIC as metrics.json of `stochnav run`; std is the sample standard
//                 deviation over seeds (0 for one seed); improvement 100 (1 - variant/baseline)
//                 per seed.
//     "fitted"    one entry per seed (seeds order): {"gyro": params(), "accel": params(),
//                 "fit_quality": {"gyro": q, "accel": q}}: the noise models the filter ran with
//                 (fitted or as given, NoiseModelPlugin::params, reporting units) and the
//                 fitter's quality (NoiseModelPlugin::fit_quality: per axis chi_square, dof,
//                 chi_square_per_dof, p_value, at_bound; null when built from params or the
//                 plugin cannot say).
//     "consistency" (null without truth) over all scored (output) epochs of all seeds:
//                 "nees_mean": the mean NEES of the 9 position/velocity/attitude error states
//                 over the N = nees_samples epochs x seeds; "nees_bounds": [lo, hi] =
//                 [chi2_0.025(9 N), chi2_0.975(9 N)] / N, the two-sided 95 % interval of that
//                 mean for a consistent filter if the N samples were independent (they are
//                 correlated in time, so the interval is narrower than the mean's real spread:
//                 a screen, not a test); "inside_3sigma": {METRIC: share of epochs with |error|
//                 <= 3 sigma}; "aids": [{"type", "dof", "attempts", "nis_mean" (accepted
//                 updates), "nis_bounds": chi2_{0.025, 0.975}(dof M) / M for M accepted}];
//                 "optimistic": a position/velocity/attitude metric inside 3-sigma on fewer
//                 than 95 % of the epochs, or nees_mean above its upper bound;
//                 "optimistic_reason"; "per_seed": the same per seed (N = that seed's epochs).
//     "pairs"     pair_json (below) for each ExperimentConfig::pairs entry.
//   table.md      the paper's Table 3 in shape: each metric, each variant (mean +/- std; marked
//                 OPTIMISTIC), and the improvement over the baseline (mean +/- std %); the
//                 consistency per variant; the paired comparisons.
//   metrics.png   each metric per variant (mean and std over seeds), the worst metric's share
//                 inside 3-sigma and the NEES mean over its upper bound.
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
  std::vector<std::pair<std::string, std::string>> pairs;  ///< ExperimentConfig::pairs
  double wall_seconds = 0.0;
};

/// Two-sided exact sign test: with n = wins + losses (ties dropped) and X ~ Binomial(n, 1/2),
/// p = min(1, 2 min(P(X <= wins), P(X >= wins))); 1 when n = 0.
double sign_test_p_value(std::size_t wins, std::size_t losses);

/// The paired comparison of variants A and B over the seeds, per metric: d_s = max abs error
/// of A minus that of B on seed s; {"a", "b", "metrics": {METRIC: {"mean_diff", "std_diff",
/// "per_seed_diff", "a_wins" (d_s < 0), "b_wins" (d_s > 0), "ties", "sign_test_p"}}}.
nlohmann::json pair_json(const ComparisonResult& result, const std::string& a,
                         const std::string& b);

/// Builds every variant's plugins before anything is simulated: each plugin is found and loaded,
/// noise models built from their params, fitters run on a synthetic probe record so that their
/// params (fit options) are checked. Throws ConfigError naming the variant; an InputError of a
/// plugin (the data it needs do not exist yet, e.g. the oracle's scenario) is not a failure
/// here. Aid params are checked when the first run builds them.
void validate_variants(const ExperimentConfig& config);

/// Refuses a comparison beyond the limits on work (core/work_limits.hpp: seeds, variants x
/// seeds) or with a seed given twice, before anything runs: ConfigError naming the limit.
void check_work_limits(const ExperimentConfig& config);

/// Runs the experiment (validate_variants first). Simulated seeds are generated under
/// out_dir/.scenarios/seed_<seed>/ (each removed at the end, on failure and on SIGINT/SIGTERM
/// too, the folder when empty). An output folder the run created is removed if it fails.
/// Throws ConfigError / InputError (the first failure of any job, naming the variant and seed).
ComparisonResult run_comparison(const ExperimentConfig& config,
                                const std::filesystem::path& out_dir, bool progress);

/// The "consistency" of variant `index` in results.json (null without truth).
nlohmann::json variant_consistency(const ComparisonResult& result, std::size_t index);

/// results.json as described above.
nlohmann::json comparison_json(const ComparisonResult& result);
/// table.md as described above.
std::string comparison_table(const ComparisonResult& result, const ExperimentConfig& config);

/// An experiment with a "sweep" (experiment_config.hpp): every level is built and its variants
/// validated first, then each runs as a normal experiment into out_dir/level_<i>/ (its own
/// results.json, table.md, plots). Writes out_dir/sweep.json {"name", "set", "values",
/// "baseline", "levels": [{"value", "dir", "results": results.json of the level}]},
/// out_dir/sweep.png (per metric, each variant's improvement over the baseline against the level,
/// mean and std over seeds; log x when the values are positive and span >= 20x) and
/// out_dir/sweep_pairs.png (each pair's difference A - B likewise). Returns sweep.json.
nlohmann::json run_sweep(const ExperimentConfig& config, const std::filesystem::path& out_dir,
                         bool progress);
/// sweep.json and the sweep plots from the document run_sweep builds.
void write_sweep_files(const nlohmann::json& sweep, const std::filesystem::path& out_dir);

/// Writes results.json, table.md and the plots (plots skipped when gnuplot is missing).
void write_comparison(const ComparisonResult& result, const ExperimentConfig& config,
                      const std::filesystem::path& out_dir);

}  // namespace stochnav

// `stochnav compare` of an experiment with a "sweep" (experiment/comparison.hpp): every level
// as a normal experiment into DIR/level_<i>/, then DIR/sweep.json and DIR/sweep.png.

#include <fmt/format.h>

#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/comparison.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/report/gnuplot.hpp"

namespace stochnav {
namespace {

namespace fs = std::filesystem;

double number(const nlohmann::json& value) {
  return value.is_number() ? value.get<double>() : std::nan("");
}

// x of each level: the value when every value is a number, else the level index.
std::vector<double> level_axis(const ExperimentSweep& sweep, bool& log_scale) {
  std::vector<double> x;
  bool numeric = true;
  for (const auto& value : sweep.values) numeric &= value.is_number();
  double low = INFINITY, high = 0.0;
  for (std::size_t i = 0; i < sweep.values.size(); ++i) {
    x.push_back(numeric ? sweep.values[i].get<double>() : static_cast<double>(i));
    low = std::min(low, x.back());
    high = std::max(high, x.back());
  }
  log_scale = numeric && low > 0.0 && high / low >= 20.0;
  return x;
}

// Nine panels (one per metric), one curve per series, mean with the seed spread (std) as error
// bars against the level. `series` names the curves; values[level][series][metric] = {mean, std}.
void plot_sweep(const std::string& title, const std::string& y_label,
                const std::vector<std::string>& series, const std::vector<double>& x, bool log_x,
                const std::vector<std::vector<std::vector<std::array<double, 2>>>>& values,
                const std::string& x_label, const fs::path& path) {
  std::string script;
  for (std::size_t c = 0; c < series.size(); ++c) {
    script += fmt::format("$s{} << EOD\n", c);
    for (std::size_t level = 0; level < x.size(); ++level) {
      script += fmt::format("{:.9g}", x[level]);
      for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
        script += fmt::format(" {:.6g} {:.6g}", values[level][c][m][0], values[level][c][m][1]);
      }
      script += '\n';
    }
    script += "EOD\n";
  }
  script += fmt::format(
      "set multiplot layout 3,3 title {} noenhanced\nset grid\nset offsets graph 0.05, graph "
      "0.05, graph 0.05, graph 0.05\nset key top left font ',7' "
      "noenhanced\nset xlabel {} noenhanced font ',8'\nset ylabel {} noenhanced font ',8'\n{}",
      gnuplot_string(title), gnuplot_string(x_label), gnuplot_string(y_label),
      log_x ? "set logscale x\n" : "");
  for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
    // A metric undefined at every level (the toolface of a vertical hole): gnuplot refuses a
    // plot without a point, so the panel is drawn empty and says so.
    bool defined = false;
    for (const auto& level : values) {
      for (const auto& curve : level) defined = defined || std::isfinite(curve[m][0]);
    }
    if (!defined) {
      script += fmt::format(
          "set title '{}: not defined in this run' noenhanced\nplot $s0 using 1:(0) notitle\n",
          kErrorMetricNames[m]);
      continue;
    }
    script += fmt::format("set title '{}' noenhanced\nplot ", kErrorMetricNames[m]);
    for (std::size_t c = 0; c < series.size(); ++c) {
      script += fmt::format("{}$s{} using 1:{}:{} with yerrorlines title {}", c == 0 ? "" : ", ",
                            c, 2 + 2 * m, 3 + 2 * m, gnuplot_string(series[c]));
    }
    script += '\n';
    if (m == 0) script += "unset key\n";
  }
  script += "unset multiplot\n";
  render_gnuplot(script, path);
}

}  // namespace

nlohmann::json run_sweep(const ExperimentConfig& config, const fs::path& out_dir, bool progress) {
  if (!config.sweep) throw ConfigError(config.file.string() + ": /sweep: missing");
  const ExperimentSweep& sweep = *config.sweep;
  // Every level is built (and its variants checked) before the first one runs.
  std::vector<ExperimentConfig> levels;
  for (std::size_t i = 0; i < sweep.values.size(); ++i) {
    levels.push_back(sweep_level(config, i));
    check_work_limits(levels.back());
    validate_variants(levels.back());
  }
  // A sweep failing at a later level leaves no folder it created.
  OutputFolder out_folder(out_dir);
  nlohmann::json document = {{"name", sweep.name},
                             {"set", sweep.set},
                             {"values", sweep.values},
                             {"baseline", config.baseline},
                             {"levels", nlohmann::json::array()}};
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const fs::path dir = out_dir / fmt::format("level_{}", i);
    const ComparisonResult result = run_comparison(levels[i], dir, progress);
    write_comparison(result, levels[i], dir);
    document["levels"].push_back({{"value", sweep.values[i]},
                                  {"dir", fmt::format("level_{}", i)},
                                  {"results", comparison_json(result)}});
  }
  write_sweep_files(document, out_dir);
  out_folder.keep();
  return document;
}

void write_sweep_files(const nlohmann::json& sweep, const fs::path& out_dir) {
  write_file_atomically(out_dir / "sweep.json", sweep.dump(2) + "\n");
  const auto& levels = sweep["levels"];
  if (levels.empty()) return;
  try {
    check_plot_request(out_dir / "sweep.png");
  } catch (const ConfigError&) {
    return;  // gnuplot missing: sweep.json is complete without the plots
  }
  ExperimentSweep axis;
  for (const auto& value : sweep["values"]) axis.values.push_back(value);
  bool log_x = false;
  const std::vector<double> x = level_axis(axis, log_x);
  const std::string x_label = sweep["name"].get<std::string>();

  // Improvement over the baseline of every other variant.
  std::vector<std::string> names;
  for (const auto& variant : levels[0]["results"]["variants"]) {
    if (variant["name"] != sweep["baseline"]) names.push_back(variant["name"]);
  }
  std::vector<std::vector<std::vector<std::array<double, 2>>>> gains(levels.size());
  for (std::size_t level = 0; level < levels.size(); ++level) {
    for (const auto& name : names) {
      std::vector<std::array<double, 2>> row(kErrorMetricCount, {NAN, NAN});
      for (const auto& variant : levels[level]["results"]["variants"]) {
        if (variant["name"] != name) continue;
        for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
          const auto& gain = variant["improvement_pct"][std::string(kErrorMetricNames[m])];
          row[m] = {number(gain["mean"]), number(gain["std"])};
        }
      }
      gains[level].push_back(row);
    }
  }
  if (!names.empty()) {
    plot_sweep("improvement over the baseline " + sweep["baseline"].get<std::string>() +
                   " (mean and std over seeds)",
               "improvement (%)", names, x, log_x, gains, x_label, out_dir / "sweep.png");
  }
  // Each named pair's difference A - B of the maximum absolute error.
  const auto& pairs = levels[0]["results"]["pairs"];
  if (pairs.empty()) return;
  std::vector<std::string> pair_names;
  for (const auto& pair : pairs) {
    pair_names.push_back(pair["a"].get<std::string>() + " - " + pair["b"].get<std::string>());
  }
  std::vector<std::vector<std::vector<std::array<double, 2>>>> diffs(levels.size());
  for (std::size_t level = 0; level < levels.size(); ++level) {
    for (const auto& pair : levels[level]["results"]["pairs"]) {
      std::vector<std::array<double, 2>> row;
      for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
        const auto& p = pair["metrics"][std::string(kErrorMetricNames[m])];
        row.push_back({number(p["mean_diff"]), number(p["std_diff"])});
      }
      diffs[level].push_back(row);
    }
  }
  plot_sweep("paired difference A - B of the maximum absolute error (mean and std over seeds)",
             "A - B", pair_names, x, log_x, diffs, x_label, out_dir / "sweep_pairs.png");
}

}  // namespace stochnav

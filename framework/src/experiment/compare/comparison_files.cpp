// The files of `stochnav compare` (experiment/comparison.hpp): results.json, table.md, plots.

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/temporary_files.hpp"
#include "stochnav/experiment/comparison.hpp"
#include "stochnav/experiment/error_plot.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/report/gnuplot.hpp"

namespace stochnav {
namespace {

// Nine panels, one per metric: each variant's mean with its std as an error bar. A metric no
// variant has a positive value of (the toolface while the hole is vertical is undefined) gets
// an empty panel saying so: gnuplot refuses a log-scale plot without a point.
void plot_metrics(const ComparisonResult& result, const std::filesystem::path& path) {
  std::array<bool, kErrorMetricCount> drawable{};
  std::string script = "$metrics << EOD\n";
  for (std::size_t v = 0; v < result.variants.size(); ++v) {
    script += fmt::format("{} \"{}\"", v, result.variants[v].name);
    for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
      double sum = 0.0, squares = 0.0;
      const auto& runs = result.variants[v].runs;
      for (const auto& run : runs) sum += run.statistics.max_abs(m);
      const double mean = sum / static_cast<double>(runs.size());
      for (const auto& run : runs) {
        squares += (run.statistics.max_abs(m) - mean) * (run.statistics.max_abs(m) - mean);
      }
      const double spread =
          runs.size() > 1 ? std::sqrt(squares / static_cast<double>(runs.size() - 1)) : 0.0;
      script += fmt::format(" {:.6g} {:.6g}", mean, spread);
      drawable[m] = drawable[m] || (std::isfinite(mean) && mean > 0.0);
    }
    // Consistency: the worst metric's share inside 3-sigma (%), and the NEES mean over its
    // upper 95 % bound (above 1: optimistic).
    const nlohmann::json consistency = variant_consistency(result, v);
    double worst = std::nan("");
    double nees_ratio = std::nan("");
    if (consistency.is_object()) {
      for (const auto& [name, share] : consistency["inside_3sigma"].items()) {
        if (share.is_number() && !(share.get<double>() >= worst)) worst = share.get<double>();
      }
      if (consistency["nees_bounds"].is_array() && consistency["nees_mean"].is_number()) {
        nees_ratio = consistency["nees_mean"].get<double>() /
                     consistency["nees_bounds"][1].get<double>();
      }
    }
    script += fmt::format(" {:.6g} {:.6g}", std::isfinite(worst) ? 100.0 * worst : 0.0,
                          std::isfinite(nees_ratio) ? nees_ratio : 0.0);
    script += '\n';
  }
  script += "EOD\n";
  script +=
      "set multiplot layout 4,3 title 'maximum absolute error per variant (mean and std over "
      "seeds)' noenhanced\nset style fill solid 0.6\nset boxwidth 0.6\nset xtics rotate by -40 "
      "noenhanced font ',8'\nset logscale y\nset grid y\nunset key\n";
  for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
    if (!drawable[m]) {
      script += fmt::format(
          "set title '{}: not defined in this run' noenhanced\nunset logscale y\n"
          "set yrange [0:1]\nplot $metrics using 1:(0):xtic(2) with boxes\n"
          "set autoscale y\nset logscale y\n",
          kErrorMetricNames[m]);
      continue;
    }
    script += fmt::format(
        "set title '{}' noenhanced\nplot $metrics using 1:{}:xtic(2) with boxes lc rgb "
        "'#4878a8', '' using 1:{}:{} with yerrorbars lc rgb 'black' pt 0\n",
        kErrorMetricNames[m], 3 + 2 * m, 3 + 2 * m, 4 + 2 * m);
  }
  const std::size_t worst_column = 3 + 2 * kErrorMetricCount;
  script += fmt::format(
      "set title 'worst metric inside 3-sigma (%, all seeds)' noenhanced\nunset logscale y\n"
      "set yrange [0:105]\nplot $metrics using 1:{}:xtic(2) with boxes lc rgb '#4878a8', 95 "
      "with lines lc rgb 'red' dt 2\nset title 'NEES mean / upper 95 % bound (>1: optimistic)' "
      "noenhanced\nset autoscale y\nset logscale y\nplot $metrics using 1:{}:xtic(2) with boxes "
      "lc rgb '#4878a8', 1 with lines lc rgb 'red' dt 2\n",
      worst_column, worst_column + 1);
  script += "unset multiplot\n";
  render_gnuplot(script, path);
}

// An earlier comparison in the same folder: its results.json (the completion mark) goes
// first, then the plots it made, so that the folder never shows old results beside new plots,
// nor an old variant's plot beside new results.
void remove_previous_comparison(const std::filesystem::path& out_dir) {
  const std::filesystem::path results = out_dir / "results.json";
  std::vector<std::string> variants;
  try {
    std::ifstream in(results);
    if (in) {
      const nlohmann::json previous = nlohmann::json::parse(in);
      for (const auto& variant : previous.at("variants")) {
        variants.push_back(variant.at("name").get<std::string>());
      }
    }
  } catch (const std::exception&) {
    // Not a comparison's results.json: remove it, keep every plot.
  }
  std::error_code ignored;
  std::filesystem::remove(results, ignored);
  std::filesystem::remove(out_dir / "metrics.png", ignored);
  for (const std::string& name : variants) {
    std::filesystem::remove(out_dir / fmt::format("errors_{}.png", name), ignored);
  }
}

}  // namespace

void write_comparison(const ComparisonResult& result, const ExperimentConfig& config,
                      const std::filesystem::path& out_dir) {
  OutputFolder folder(out_dir);  // one writer (nested in the caller's lock when it holds one)
  remove_previous_comparison(out_dir);
  try {
    check_plot_request(out_dir / "metrics.png");
    plot_metrics(result, out_dir / "metrics.png");
    for (const auto& variant : result.variants) {
      if (variant.runs.empty() || variant.runs.front().error_series.size() < 2) continue;
      plot_navigation_errors(
          variant.runs.front().error_series,
          fmt::format("{}: errors and 3-sigma bounds (seed {})", variant.name,
                      result.seeds.front()),
          out_dir / fmt::format("errors_{}.png", variant.name));
    }
  } catch (const ConfigError&) {
    // gnuplot missing: the numbers below are complete without the plots.
  }
  write_file_atomically(out_dir / "table.md", comparison_table(result, config));
  // Last: its presence says the folder holds one whole comparison.
  write_file_atomically(out_dir / "results.json", comparison_json(result).dump(2) + "\n");
  folder.keep();
}

}  // namespace stochnav

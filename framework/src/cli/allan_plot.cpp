#include "allan_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "model_overlay.hpp"
#include "stochnav/report/gnuplot.hpp"

namespace stochnav::cli {

void plot_allan_deviation(const std::vector<DeviationPoint>& points, const Record& record,
                          Deviation kind, const std::string& fit_path,
                          const std::string& plot_path) {
  std::vector<double> tau, deviation, lower, upper;
  for (const auto& p : points) {
    tau.push_back(p.tau_s);
    deviation.push_back(p.deviation);
    lower.push_back(p.lower > 0.0 ? p.lower : p.deviation);
    upper.push_back(p.upper > 0.0 ? p.upper : p.deviation);
  }
  std::string script = gnuplot_datablock("measured", {&tau, &deviation, &lower, &upper});
  std::string plots = fmt::format(
      "$measured using 1:2:3:4 with yerrorlines lw 1.5 pt 7 ps 0.6 lc rgb '#1f77b4' "
      "title '{} (68.3 % interval)'",
      deviation_name(kind));
  if (!fit_path.empty()) {
    const ModelOverlay overlay = model_overlay(fit_path, record, tau.front(), tau.back());
    script += overlay.datablocks;
    plots += overlay.plot_clauses;
  }
  script += fmt::format(
      "set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\n"
      "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
      "set xlabel 'averaging time tau (s)'\nset ylabel '{} ({})'\n"
      "set title {} noenhanced\nset key top right\n",
      deviation_name(kind), unit_name(record.unit),
      gnuplot_string(record.source + " [" + record.column + "]"));
  // Fitted terms fall far below the data at some taus: keep the view on the measurement.
  const double lowest = *std::min_element(lower.begin(), lower.end());
  const double highest = *std::max_element(upper.begin(), upper.end());
  script += fmt::format("set yrange [{:.6g}:{:.6g}]\n", lowest / 4.0, highest * 4.0);
  script += "plot " + plots + "\n";
  render_gnuplot(script, plot_path);
}

}  // namespace stochnav::cli

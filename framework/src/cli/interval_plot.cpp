#include "interval_plot.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "stochnav/report/gnuplot.hpp"

namespace stochnav::cli {

void plot_with_intervals(IntervalPlot plot, const Record& record, const std::string& fit_path,
                         const std::string& plot_path) {
  for (std::size_t i = 0; i < plot.y.size(); ++i) {
    if (!(plot.lower[i] > 0.0)) plot.lower[i] = plot.y[i];
    if (!(plot.upper[i] > 0.0)) plot.upper[i] = plot.y[i];
  }
  std::string script = gnuplot_datablock("measured", {&plot.x, &plot.y, &plot.lower, &plot.upper});
  std::string plots = fmt::format(
      "$measured using 1:2:3:4 with yerrorlines lw 1.5 pt 7 ps 0.6 lc rgb '#1f77b4' title {}",
      gnuplot_string(plot.title));
  if (!fit_path.empty()) {
    const ModelOverlay overlay =
        model_overlay(fit_path, record, plot.x.front(), plot.x.back(), plot.model_curve);
    script += overlay.datablocks;
    plots += overlay.plot_clauses;
  }
  script += fmt::format(
      "set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\n"
      "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
      "set xlabel {}\nset ylabel {}\nset title {} noenhanced\nset key top right\n",
      gnuplot_string(plot.x_label), gnuplot_string(plot.y_label),
      gnuplot_string(record.source + " [" + record.column + "]"));
  const double lowest = *std::min_element(plot.lower.begin(), plot.lower.end());
  const double highest = *std::max_element(plot.upper.begin(), plot.upper.end());
  script += fmt::format("set yrange [{:.6g}:{:.6g}]\n", lowest / plot.y_margin,
                        highest * plot.y_margin);
  script += "plot " + plots + "\n";
  render_gnuplot(script, plot_path);
}

}  // namespace stochnav::cli

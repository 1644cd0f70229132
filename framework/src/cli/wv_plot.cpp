#include "wv_plot.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "model_overlay.hpp"
#include "stochnav/report/gnuplot.hpp"

namespace stochnav::cli {

void plot_wavelet_variance(const std::vector<WaveletVariancePoint>& points, const Record& record,
                           bool robust, const std::string& fit_path, const std::string& plot_path) {
  std::vector<double> scale, variance, lower, upper;
  for (const auto& p : points) {
    scale.push_back(p.scale_s);
    variance.push_back(p.variance);
    lower.push_back(p.lower > 0.0 ? p.lower : p.variance);
    upper.push_back(p.upper > 0.0 ? p.upper : p.variance);
  }
  std::string script = gnuplot_datablock("measured", {&scale, &variance, &lower, &upper});
  std::string plots = fmt::format(
      "$measured using 1:2:3:4 with yerrorlines lw 1.5 pt 7 ps 0.6 lc rgb '#1f77b4' "
      "title '{} wavelet variance (95 % interval)'",
      robust ? "robust" : "classical");
  if (!fit_path.empty()) {
    const ModelOverlay overlay = model_overlay(fit_path, record, scale.front(), scale.back(),
                                               ModelCurve::kHaarWaveletVariance);
    script += overlay.datablocks;
    plots += overlay.plot_clauses;
  }
  script += fmt::format(
      "set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\n"
      "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
      "set xlabel 'scale tau (s)'\nset ylabel 'Haar wavelet variance (({})^2)'\n"
      "set title {} noenhanced\nset key top right\n",
      unit_name(record.unit), gnuplot_string(record.source + " [" + record.column + "]"));
  // Model terms fall far below the data at some scales: keep the view on the measurement.
  const double lowest = *std::min_element(lower.begin(), lower.end());
  const double highest = *std::max_element(upper.begin(), upper.end());
  script += fmt::format("set yrange [{:.6g}:{:.6g}]\n", lowest / 10.0, highest * 10.0);
  script += "plot " + plots + "\n";
  render_gnuplot(script, plot_path);
}

}  // namespace stochnav::cli

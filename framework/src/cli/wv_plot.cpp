#include "wv_plot.hpp"

#include <fmt/format.h>

#include <utility>

#include "interval_plot.hpp"

namespace stochnav::cli {

void plot_wavelet_variance(const std::vector<WaveletVariancePoint>& points, const Record& record,
                           bool robust, const std::string& fit_path, const std::string& plot_path) {
  IntervalPlot plot{
      .title = std::string(robust ? "robust" : "classical") + " wavelet variance (95 % interval)",
      .x_label = "scale tau (s)",
      .y_label = fmt::format("Haar wavelet variance (({})^2)", unit_name(record.unit)),
      .model_curve = ModelCurve::kHaarWaveletVariance,
      .y_margin = 10.0};
  for (const auto& p : points) {
    plot.x.push_back(p.scale_s);
    plot.y.push_back(p.variance);
    plot.lower.push_back(p.lower);
    plot.upper.push_back(p.upper);
  }
  plot_with_intervals(std::move(plot), record, fit_path, plot_path);
}

}  // namespace stochnav::cli

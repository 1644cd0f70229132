#include "allan_plot.hpp"

#include <fmt/format.h>

#include <utility>

#include "interval_plot.hpp"

namespace stochnav::cli {

void plot_allan_deviation(const std::vector<DeviationPoint>& points, const Record& record,
                          Deviation kind, const std::string& fit_path,
                          const std::string& plot_path) {
  IntervalPlot plot{.title = std::string(deviation_name(kind)) + " (68.3 % interval)",
                    .x_label = "averaging time tau (s)",
                    .y_label =
                        fmt::format("{} ({})", deviation_name(kind), unit_name(record.unit)),
                    .model_curve = ModelCurve::kAllanDeviation,
                    .y_margin = 4.0};
  for (const auto& p : points) {
    plot.x.push_back(p.tau_s);
    plot.y.push_back(p.deviation);
    plot.lower.push_back(p.lower);
    plot.upper.push_back(p.upper);
  }
  plot_with_intervals(std::move(plot), record, fit_path, plot_path);
}

}  // namespace stochnav::cli

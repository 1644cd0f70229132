#pragma once
// The log-log plot of a measured curve with its confidence interval bars (allan, wv), and
// optionally a noise model's implied curve and terms over it (model_overlay.hpp).

#include <string>
#include <vector>

#include "model_overlay.hpp"
#include "stochnav/io/record.hpp"

namespace stochnav::cli {

struct IntervalPlot {
  std::vector<double> x, y, lower, upper;  ///< x: tau or scale (s); y and its interval
  std::string title;                       ///< the measured series' key entry
  std::string x_label, y_label;
  ModelCurve model_curve = ModelCurve::kAllanDeviation;  ///< what the model overlay draws
  /// The y range is the interval's span widened by this factor each way: model terms fall far
  /// below the data at some taus, and the view stays on the measurement.
  double y_margin = 4.0;
};

/// Draws `plot` to `plot_path` (.png or .svg); a bound <= 0 is drawn at the value. `record`
/// gives the title (source and column); `fit_path`, when not empty, names a noise-model JSON in
/// the record's units.
void plot_with_intervals(IntervalPlot plot, const Record& record, const std::string& fit_path,
                         const std::string& plot_path);

}  // namespace stochnav::cli

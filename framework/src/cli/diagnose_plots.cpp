#include "diagnose_plots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/model/allan_variance.hpp"
#include "stochnav/report/gnuplot.hpp"
#include "stochnav/stats/davar.hpp"

namespace stochnav::cli {
namespace {

std::string axes(const std::string& ylabel, const std::string& title) {
  return fmt::format(
      "set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\n"
      "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
      "set xlabel 'averaging time tau (s)'\nset ylabel {} noenhanced\n"
      "set title {} noenhanced\nset key bottom left\n",
      gnuplot_string(ylabel), gnuplot_string(title));
}

std::vector<double> model_curve(const NoiseModel& model, const std::vector<double>& tau,
                                double duration_s, double per_natural) {
  const NoiseModel equivalent = stationary_equivalent(model, duration_s).model;
  std::vector<double> curve;
  for (double t : tau) curve.push_back(std::sqrt(allan_variance(equivalent, t)) * per_natural);
  return curve;
}

}  // namespace

void plot_diagnose_step(const MeasuredStatistics& measured, const ModelAssessment* before,
                        const ModelAssessment& after, const std::string& label,
                        const Record& record, const std::filesystem::path& output) {
  const double per_natural = 1.0 / si_per_unit(measured.unit);
  std::vector<double> tau, deviation;
  for (const auto& p : measured.dense) {
    tau.push_back(p.tau_s);
    deviation.push_back(p.deviation);
  }
  std::vector<double> octave_tau, octave_dev, lower, upper;
  for (const auto& p : measured.octave) {
    if (!(p.deviation > 0.0)) continue;
    octave_tau.push_back(p.tau_s);
    octave_dev.push_back(p.deviation);
    lower.push_back(p.lower > 0.0 ? p.lower : p.deviation);
    upper.push_back(p.upper > 0.0 ? p.upper : p.deviation);
  }
  std::string script = gnuplot_datablock("measured", {&tau, &deviation});
  script += gnuplot_datablock("octave", {&octave_tau, &octave_dev, &lower, &upper});
  std::string plots;
  const auto& band = after.band;
  if (!band.low.empty()) {
    std::vector<double> low, high;
    for (std::size_t j = 0; j < band.low.size(); ++j) {
      low.push_back(band.low[j] * per_natural);
      high.push_back(band.high[j] * per_natural);
    }
    script += gnuplot_datablock("band", {&band.tau_s, &low, &high});
    plots += fmt::format(
        "$band using 1:2:3 with filledcurves fs transparent solid 0.25 noborder lc rgb "
        "'#d62728' title 'model: {} simulated records (min-max)', ",
        band.seeds);
  }
  const auto after_curve = model_curve(after.model, tau, measured.duration_s, per_natural);
  script += gnuplot_datablock("after", {&tau, &after_curve});
  plots +=
      "$measured using 1:2 with lines lw 1.5 lc rgb '#1f77b4' title 'measured OADEV', "
      "$octave using 1:2:3:4 with yerrorbars pt 7 ps 0.6 lc rgb '#1f77b4' "
      "title 'octave taus (68.3 % interval)', ";
  plots += fmt::format(
      "$after using 1:2 with lines lw 2.5 lc rgb '#d62728' title 'model {} "
      "(gap {:.3g})'",
      before ? "after" : "as given", after.gap.value);
  if (before != nullptr) {
    const auto before_curve = model_curve(before->model, tau, measured.duration_s, per_natural);
    script += gnuplot_datablock("before", {&tau, &before_curve});
    plots += fmt::format(
        ", $before using 1:2 with lines dt 2 lw 2 lc rgb '#7f7f7f' title "
        "'model before (gap {:.3g})'",
        before->gap.value);
  }
  script += axes(fmt::format("Allan deviation ({})", unit_name(measured.unit)),
                 fmt::format("{} [{}]: {}", record.source, record.column, label));
  const double lowest = *std::min_element(lower.begin(), lower.end());
  const double highest = *std::max_element(upper.begin(), upper.end());
  script += fmt::format("set yrange [{:.6g}:{:.6g}]\n", lowest / 4.0, highest * 4.0);
  script += "plot " + plots + "\n";
  render_gnuplot(script, output);
}

void plot_diagnose_davar(const Record& record, const MeasuredStatistics& measured,
                         const StationarityTest& test, const NoiseModel& model,
                         const std::filesystem::path& output) {
  const auto& windows = measured.windows;
  if (windows.avar.empty()) return;
  const std::size_t window = static_cast<std::size_t>(
      std::llround((windows.end_s[0] - windows.start_s[0]) * record.rate_hz));
  DavarOptions options{.window = window, .step = std::max<std::size_t>(1, window / 2)};
  auto m = default_davar_m_values(window, record.kind);
  if (m.size() > 4) m.resize(4);
  options.m_values = m;
  const DavarResult davar = dynamic_allan_deviation(record, options);
  std::string script;
  std::string plots;
  for (std::size_t j = 0; j < davar.tau_s.size(); ++j) {
    std::vector<double> column;
    for (const auto& row : davar.adev) column.push_back(row[j]);
    const std::string name = fmt::format("tau{}", j);
    script += gnuplot_datablock(name, {&davar.time_s, &column});
    plots +=
        fmt::format("{}${} using 1:2 with linespoints pt 7 ps 0.4 title 'DAVAR tau = {:.4g} s'",
                    plots.empty() ? "" : ", ", name, davar.tau_s[j]);
  }
  // Expected short-tau level under the model: quiet level times the window's scale^2.
  const double per_natural = 1.0 / si_per_unit(measured.unit);
  std::vector<double> time, expected;
  for (std::size_t k = 0; k < windows.avar.size(); ++k) {
    const double factor = mean_scale_squared(model, windows.start_s[k], windows.end_s[k]);
    const double level = std::sqrt(std::exp(test.reference_log) * factor) * per_natural;
    time.push_back(windows.start_s[k]);
    expected.push_back(level);
    time.push_back(windows.end_s[k]);
    expected.push_back(level);
  }
  script += gnuplot_datablock("expected", {&time, &expected});
  plots += fmt::format(
      ", $expected using 1:2 with lines lw 2 dt 2 lc rgb '#d62728' title "
      "'final model at tau = {:.4g} s (quiet level x scale)'",
      davar.tau_s.front());
  script += fmt::format(
      "set logscale y\nset format y '10^{{%L}}'\nset grid lc rgb '#dddddd'\n"
      "set xlabel 'record time (s)'\nset ylabel 'Allan deviation ({})' noenhanced\n"
      "set title {} noenhanced\nset key outside bottom center horizontal\n",
      unit_name(measured.unit),
      gnuplot_string(fmt::format("{} [{}]: DAVAR, window {} samples", record.source,
                                 record.column, window)));
  script += "plot " + plots + "\n";
  render_gnuplot(script, output);
}

}  // namespace stochnav::cli

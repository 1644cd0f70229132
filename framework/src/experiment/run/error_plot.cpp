#include "stochnav/experiment/error_plot.hpp"

#include <fmt/format.h>

#include "stochnav/report/gnuplot.hpp"

namespace stochnav {

void plot_navigation_errors(const std::vector<ErrorSample>& series, const std::string& title,
                            const std::filesystem::path& path) {
  std::string script = "$errors << EOD\n";
  for (const ErrorSample& s : series) {
    script += fmt::format("{:.3f}", s.t_s);
    for (double e : s.errors) script += fmt::format(" {:.6g}", e);
    for (double e : s.sigma) script += fmt::format(" {:.6g}", 3.0 * e);
    script += '\n';
  }
  script += "EOD\n";
  script +=
      fmt::format("set multiplot layout 3,1 title {} noenhanced\n", gnuplot_string(title)) +
      "set key outside right noenhanced\nset grid\n";
  const char* panels[3][2] = {{"position error (m)", ""},
                              {"velocity error (m/s)", ""},
                              {"attitude error (deg)", "time (s)"}};
  const char* colours[3] = {"#1f77b4", "#d62728", "#2ca02c"};
  for (int panel = 0; panel < 3; ++panel) {
    script += fmt::format("set ylabel '{}'\nset xlabel '{}'\nplot ", panels[panel][0],
                          panels[panel][1]);
    const int metric0 = panel == 0 ? 0 : panel == 1 ? 6 : 3;
    for (int k = 0; k < 3; ++k) {
      const int column = 2 + metric0 + k;
      const int sigma_column = column + static_cast<int>(kErrorMetricCount);
      script += fmt::format(
          "$errors using 1:{} with lines lc rgb '{}' title '{}', "
          "'' using 1:{} with lines dt 2 lc rgb '{}' notitle, "
          "'' using 1:(-${}) with lines dt 2 lc rgb '{}' notitle{}",
          column, colours[k], kErrorMetricNames[static_cast<std::size_t>(metric0 + k)],
          sigma_column, colours[k], sigma_column, colours[k], k < 2 ? ", " : "\n");
    }
  }
  script += "unset multiplot\n";
  render_gnuplot(script, path);
}

}  // namespace stochnav

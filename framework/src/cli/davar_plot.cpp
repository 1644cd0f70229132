#include "davar_plot.hpp"

#include <fmt/format.h>

#include <sstream>

#include "stochnav/report/gnuplot.hpp"

namespace stochnav::cli {

void plot_davar(const DavarPlotData& data, const std::string& title, const std::string& unit,
                const std::string& plot_path) {
  // pm3d wants grid scans separated by blank lines: one scan per analysis time.
  std::ostringstream grid;
  grid.precision(8);
  grid << "$davar << EOD\n";
  for (std::size_t k = 0; k < data.rows(); ++k) {
    for (std::size_t j = 0; j < data.tau_s.size(); ++j) {
      grid << data.time_s[k] << ' ' << data.tau_s[j] << ' ' << data.deviation[k][j] << '\n';
    }
    grid << '\n';
  }
  grid << "EOD\n";
  std::string script = grid.str();
  script += fmt::format(
      "set view map\nset logscale y\nset logscale cb\nset format y '10^{{%L}}'\n"
      "set format cb '10^{{%L}}'\nset xlabel 'analysis time (s)'\n"
      "set ylabel 'averaging time tau (s)'\nset cblabel 'Allan deviation ({})'\n"
      "set title {} noenhanced\nset palette rgb 33,13,10\nunset key\n"
      "set pm3d map corners2color c1\n",
      unit, gnuplot_string("DAVAR of " + title));
  script += data.rows() > 1 ? "splot $davar using 1:2:3 with pm3d\n"
                            : "plot $davar using 2:3 with linespoints\n";
  render_gnuplot(script, plot_path);
}

}  // namespace stochnav::cli

#pragma once
// The heat map of `stochnav davar --plot`: deviation over analysis time and tau.

#include <string>
#include <vector>

#include "stochnav/stats/davar.hpp"

namespace stochnav::cli {

struct DavarPlotData {
  std::vector<double> tau_s;
  std::vector<double> time_s;
  std::vector<std::vector<double>> deviation;  ///< [window][tau]

  void add_row(const DavarRow& row) {
    time_s.push_back(row.time_s);
    deviation.push_back(row.deviation);
  }
  std::size_t rows() const { return time_s.size(); }
};

void plot_davar(const DavarPlotData& data, const std::string& title, const std::string& unit,
                const std::string& plot_path);

}  // namespace stochnav::cli

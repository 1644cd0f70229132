#pragma once
// The R package `wv`'s wavelet-variance tables (../shared/data/gmwm/*_wv_ref.csv, SOURCES.md
// there): sensor, freq, n, channel, scale_s, wv, ci_low, ci_high; quoted text cells.

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace stochnav::testing {

struct WvReferenceRow {
  double scale_s = 0.0;
  double wv = 0.0;
  double ci_low = 0.0;
  double ci_high = 0.0;
};

/// Rows by channel name ("Gyro. X", ...), in file order (ascending scale).
inline std::map<std::string, std::vector<WvReferenceRow>> read_wv_reference(
    const std::string& path) {
  std::map<std::string, std::vector<WvReferenceRow>> table;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) {
      if (cell.size() >= 2 && cell.front() == '"') cell = cell.substr(1, cell.size() - 2);
      cells.push_back(cell);
    }
    if (cells.size() != 8) continue;
    table[cells[3]].push_back(
        {std::stod(cells[4]), std::stod(cells[5]), std::stod(cells[6]), std::stod(cells[7])});
  }
  return table;
}

/// The column of ../shared/data/imu-static/adis16405_imu1_static_100hz.csv for each channel of
/// adis_wv_ref.csv.
inline const std::map<std::string, std::string>& adis_wv_channel_columns() {
  static const std::map<std::string, std::string> columns = {
      {"Gyro. X", "gyro_x_dps"}, {"Gyro. Y", "gyro_y_dps"}, {"Gyro. Z", "gyro_z_dps"},
      {"Accel. X", "acc_x_g"},   {"Accel. Y", "acc_y_g"},   {"Accel. Z", "acc_z_g"}};
  return columns;
}

}  // namespace stochnav::testing

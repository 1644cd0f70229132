#pragma once
// states.csv of a navigation run: the filter's sensor-error states beyond the navigation ones,
// each with its 1-sigma, one row per output epoch (decimated like nav.csv).
//
// Columns: t (s); then, for every state of every sensor-error block of the layout in layout
// order, its estimate and, after all estimates, the same names with "_sigma":
//   accel_bias_{x,y,z}_m_s2, gyro_bias_{x,y,z}_deg_h          body axes
//   gyro_scale_factor_{x,y,z}_ppm, accel_scale_factor_...     when estimated
//   gyro.<type>_<i>_si, accel.<type>_<i>_si                   a noise model's augmented
//       states, in the model's natural SI units (rad/s or m/s^2 for a state the sensor map
//       passes on unchanged, as Gauss-Markov's; a shaping state's own units otherwise)
//   gyro.<type>_error_{x,y,z}_deg_h, accel.<type>_error_{x,y,z}_m_s2
//       the sensor error those states make, M x, per body axis (sigma: sqrt diag M P M^T)
// The navigation states' estimates are nav.csv's and their sigmas covariance.csv's.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "run/run_files.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav {

class StatesFile final {
 public:
  /// `layout`: the navigator's; `gyro`, `accel`: its noise models (their sensor maps).
  StatesFile(const std::filesystem::path& path, const plugin::StateLayout& layout,
             const plugin::NoiseModelPlugin& gyro, const plugin::NoiseModelPlugin& accel);

  /// One row at the navigator's current time.
  void write(const MwdNavigator& navigator);
  void commit() { csv_.commit(); }

 private:
  // One column group: states [offset, offset + size) of the error state, scaled into the
  // column unit; or (with a sensor map) the sensor error M x those states make.
  struct Columns {
    int offset = 0;
    int size = 0;
    double scale = 1.0;
    Eigen::MatrixXd sensor_map;  // 3 x size, empty for the states themselves
  };
  static std::string header(const plugin::StateLayout& layout,
                            const plugin::NoiseModelPlugin& gyro,
                            const plugin::NoiseModelPlugin& accel, std::vector<Columns>& columns);

  std::vector<Columns> columns_;
  CsvOutput csv_;
  Eigen::VectorXd estimate_;  // the whole error state's estimates, scratch
};

}  // namespace stochnav

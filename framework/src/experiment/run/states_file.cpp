#include "run/states_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "stochnav/core/angles.hpp"
#include "stochnav/io/csv_numbers.hpp"

namespace stochnav {
namespace {

constexpr double kDegPerHourPerRadPerSecond_states = kDegPerRad * 3600.0;
constexpr double kPartsPerMillion = 1e6;
constexpr std::string_view kAxisNames[3] = {"x", "y", "z"};

bool is_navigation_block(std::string_view name) {
  return name == "position" || name == "velocity" || name == "attitude";
}

}  // namespace

std::string StatesFile::header(const plugin::StateLayout& layout,
                               const plugin::NoiseModelPlugin& gyro,
                               const plugin::NoiseModelPlugin& accel,
                               std::vector<Columns>& columns) {
  std::vector<std::string> names;
  const auto per_axis = [&](const std::string& stem, std::string_view unit) {
    for (std::string_view axis : kAxisNames) names.push_back(fmt::format("{}_{}_{}", stem, axis, unit));
  };
  for (const plugin::StateBlock& block : layout.blocks()) {
    if (is_navigation_block(block.name) || block.size == 0) continue;
    if (block.name == "accel_bias") {
      columns.push_back({block.offset, 3, 1.0, {}});
      per_axis(block.name, "m_s2");
    } else if (block.name == "gyro_bias") {
      columns.push_back({block.offset, 3, kDegPerHourPerRadPerSecond_states, {}});
      per_axis(block.name, "deg_h");
    } else if (block.name == "gyro_scale_factor" || block.name == "accel_scale_factor") {
      columns.push_back({block.offset, 3, kPartsPerMillion, {}});
      per_axis(block.name, "ppm");
    } else {
      // A noise model's augmented block, "gyro.<type>" or "accel.<type>".
      const bool is_gyro = block.name.starts_with("gyro.");
      const plugin::NoiseModelPlugin& model = is_gyro ? gyro : accel;
      columns.push_back({block.offset, block.size, 1.0, {}});
      for (int i = 0; i < block.size; ++i) names.push_back(fmt::format("{}_{}_si", block.name, i));
      Eigen::MatrixXd map = Eigen::MatrixXd::Zero(3, block.size);
      model.augmented_sensor_map(map);
      columns.push_back(
          {block.offset, block.size, is_gyro ? kDegPerHourPerRadPerSecond_states : 1.0, map});
      per_axis(block.name + "_error", is_gyro ? "deg_h" : "m_s2");
    }
  }
  std::string text = "t";
  for (const std::string& name : names) text += "," + name;
  for (const std::string& name : names) text += "," + name + "_sigma";
  return text;
}

StatesFile::StatesFile(const std::filesystem::path& path, const plugin::StateLayout& layout,
                       const plugin::NoiseModelPlugin& gyro, const plugin::NoiseModelPlugin& accel)
    : csv_(path, header(layout, gyro, accel, columns_)), estimate_(layout.size()) {}

void StatesFile::write(const MwdNavigator& navigator) {
  estimate_.setZero();
  for (const plugin::StateBlock& block : navigator.layout().blocks()) {
    if (is_navigation_block(block.name) || block.size == 0) continue;
    estimate_.segment(block.offset, block.size) = navigator.block_estimate(block.name);
  }
  const Eigen::MatrixXd& p = navigator.covariance();
  std::string& out = csv_.buffer();
  append_fixed(out, navigator.state().t_s, 3);
  for (bool sigmas : {false, true}) {
    for (const Columns& group : columns_) {
      const auto states = estimate_.segment(group.offset, group.size);
      const auto covariance = p.block(group.offset, group.offset, group.size, group.size);
      // One column per state, or per body axis of the sensor error M x (sigma: sqrt of
      // diag M P M^T), formatted as computed: no temporaries per row.
      const bool mapped = group.sensor_map.size() > 0;
      for (int column = 0; column < (mapped ? 3 : group.size); ++column) {
        double value = 0.0;
        if (!mapped) {
          value = sigmas ? std::sqrt(std::max(0.0, covariance(column, column))) : states(column);
        } else if (!sigmas) {
          value = group.sensor_map.row(column).dot(states);
        } else {
          const auto m = group.sensor_map.row(column);
          double variance = 0.0;
          for (int i = 0; i < group.size; ++i) {
            for (int j = 0; j < group.size; ++j) variance += m(i) * covariance(i, j) * m(j);
          }
          value = std::sqrt(std::max(0.0, variance));
        }
        out += ',';
        append_general(out, value * group.scale, 6);
      }
    }
  }
  out += '\n';
  csv_.flush_if_full();
}

}  // namespace stochnav

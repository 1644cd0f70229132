#include "stochnav/plugin/state_layout.hpp"

#include <stdexcept>

#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav::plugin {

StateLayout::StateLayout() {
  add_block("position", 3);
  add_block("velocity", 3);
  add_block("attitude", 3);
  add_block("accel_bias", 3);
  add_block("gyro_bias", 3);
}

int StateLayout::add_block(std::string name, int size) {
  if (size < 0) throw std::invalid_argument("StateLayout::add_block: negative size for " + name);
  if (find(name) != nullptr) {
    throw std::invalid_argument("StateLayout::add_block: block '" + name + "' already exists");
  }
  const int offset = size_;
  blocks_.push_back({std::move(name), offset, size});
  size_ += size;
  return offset;
}

const StateBlock* StateLayout::find(std::string_view name) const {
  for (const auto& block : blocks_) {
    if (block.name == name) return &block;
  }
  return nullptr;
}

StateLayout assign_state_layout(NoiseModelPlugin& gyro, NoiseModelPlugin& accel,
                                const SensorErrorStates& sensor_errors) {
  if (gyro.group() != SensorGroup::kGyro || accel.group() != SensorGroup::kAccel) {
    throw std::invalid_argument("assign_state_layout: models given for the wrong sensor groups");
  }
  StateLayout layout;
  if (sensor_errors.gyro_scale_factor) layout.add_block("gyro_scale_factor", 3);
  if (sensor_errors.accel_scale_factor) layout.add_block("accel_scale_factor", 3);
  const auto add = [&layout](NoiseModelPlugin& model) {
    const int n = model.augmented_size();
    const int offset = layout.add_block(
        std::string(sensor_group_name(model.group())) + "." + std::string(model.type()), n);
    return n > 0 ? offset : -1;
  };
  const int gyro_offset = add(gyro);
  const int accel_offset = add(accel);
  gyro.set_placement({core_state::kGyroBias, gyro_offset, layout.size()});
  accel.set_placement({core_state::kAccelBias, accel_offset, layout.size()});
  return layout;
}

}  // namespace stochnav::plugin

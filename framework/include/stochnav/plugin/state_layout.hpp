#pragma once
// The filter's error state is owned by the runtime: plugins declare block sizes
// (NoiseModelPlugin::augmented_size) and receive their offsets (NoiseModelPlugin::placement).
//
// Layout: the 15 core states, then the optional scale-factor blocks ("gyro_scale_factor",
// "accel_scale_factor", 3 states each, dimensionless: the sensor reads (1 + s) times the truth,
// per body axis), then the gyro model's augmented block, then the accel model's.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace stochnav::plugin {

class NoiseModelPlugin;

/// Offsets of the 15 core error states (dx = x_estimated - x_true).
namespace core_state {
inline constexpr int kPosition = 0;   ///< dr, ENU position error (m), 3
inline constexpr int kVelocity = 3;   ///< dv_n, ENU velocity error (m/s), 3
/// phi, attitude error in n (rad), 3: C_nb_est = (I - [phi x]) C_nb_true
inline constexpr int kAttitude = 6;
inline constexpr int kAccelBias = 9;  ///< b_a, accelerometer bias in b (m/s^2), 3
inline constexpr int kGyroBias = 12;  ///< b_g, gyro bias in b (rad/s), 3
inline constexpr int kSize = 15;
}  // namespace core_state

struct StateBlock {
  std::string name;  ///< "position", ..., "gyro_bias", "gyro.<type>", "accel.<type>"
  int offset = 0;
  int size = 0;
};

class StateLayout {
 public:
  /// The core blocks only.
  StateLayout();

  /// Appends a block of `size` >= 0 states; returns its offset. Throws std::invalid_argument
  /// for a negative size or a name already used.
  int add_block(std::string name, int size);

  int size() const { return size_; }
  std::span<const StateBlock> blocks() const { return blocks_; }
  /// The block called `name`, or nullptr.
  const StateBlock* find(std::string_view name) const;

 private:
  std::vector<StateBlock> blocks_;
  int size_ = 0;
};

/// Which optional sensor-error blocks follow the core states.
struct SensorErrorStates {
  bool gyro_scale_factor = false;   ///< block "gyro_scale_factor", 3 states
  bool accel_scale_factor = false;  ///< block "accel_scale_factor", 3 states
};

/// Lays out the error state for a filter using these models (core, the optional scale-factor
/// blocks, then gyro and accel augmented blocks) and gives each model its StatePlacement.
StateLayout assign_state_layout(NoiseModelPlugin& gyro, NoiseModelPlugin& accel,
                                const SensorErrorStates& sensor_errors = {});

}  // namespace stochnav::plugin

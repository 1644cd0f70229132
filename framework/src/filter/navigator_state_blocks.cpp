// MwdNavigator's state blocks by name, and the covariance at the current epoch: what a host
// embedding the navigator reads besides the navigation state.
#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "stochnav/filter/mwd_navigator.hpp"

namespace stochnav {
namespace {

const plugin::StateBlock& named_block(const plugin::StateLayout& layout, std::string_view name,
                                      std::string_view caller) {
  if (const plugin::StateBlock* block = layout.find(name)) return *block;
  std::string names;
  for (const plugin::StateBlock& block : layout.blocks()) {
    names += (names.empty() ? "" : ", ") + block.name;
  }
  throw std::invalid_argument(
      fmt::format("MwdNavigator::{}: no state block '{}'; the layout has {}", caller, name, names));
}

}  // namespace

Eigen::VectorXd MwdNavigator::block_estimate(std::string_view name) const {
  const plugin::StateBlock& block = named_block(layout_, name, "block_estimate");
  if (name == "accel_bias") return accel_bias_b_;
  if (name == "gyro_bias") return gyro_bias_b_;
  if (name == "gyro_scale_factor") return gyro_scale_.estimate;
  if (name == "accel_scale_factor") return accel_scale_.estimate;
  for (const AugmentedGroup* group : {&gyro_augmented_, &accel_augmented_}) {
    if (group->size > 0 && group->offset == block.offset) return group->estimate;
  }
  if (block.size == 0) return Eigen::VectorXd();  // a noise model without augmented states
  throw std::invalid_argument(fmt::format(
      "MwdNavigator::block_estimate: '{}' is a navigation block: its estimate is state()", name));
}

Eigen::MatrixXd MwdNavigator::block_covariance(std::string_view name) const {
  const plugin::StateBlock& block = named_block(layout_, name, "block_covariance");
  return filter_.covariance().block(block.offset, block.offset, block.size, block.size);
}

const Eigen::MatrixXd& MwdNavigator::covariance_now() {
  if (fast_.interval_s > 0.0) propagate_covariance();
  return filter_.covariance();
}

}  // namespace stochnav

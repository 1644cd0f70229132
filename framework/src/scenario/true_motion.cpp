#include "stochnav/scenario/true_motion.hpp"

#include "motion_models.hpp"

namespace stochnav {

TrueMotion::~TrueMotion() = default;

std::unique_ptr<TrueMotion> make_true_motion(const ScenarioConfig& config, std::uint64_t seed) {
  if (config.kind == ScenarioKind::kDrilling) {
    return std::make_unique<scenario_detail::DrillingMotion>(config);
  }
  return std::make_unique<scenario_detail::VibrationTableMotion>(config, seed);
}

}  // namespace stochnav

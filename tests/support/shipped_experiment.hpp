#pragma once
// A shipped experiment (configs/experiments/NAME.json) to change and write elsewhere.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "json_file.hpp"

namespace stochnav::testing {

/// configs/experiments/`name`.json with its data/scenario_config made absolute, so that the
/// experiment still finds its scenario when written (changed) into a test's folder.
inline nlohmann::json shipped_experiment(const std::string& name) {
  const std::filesystem::path experiments =
      std::filesystem::path(STOCHNAV_SOURCE_DIR) / "configs" / "experiments";
  nlohmann::json experiment = read_json(experiments / (name + ".json"));
  auto& data = experiment["data"];
  data["scenario_config"] =
      (experiments / data["scenario_config"].get<std::string>()).lexically_normal().string();
  return experiment;
}

}  // namespace stochnav::testing

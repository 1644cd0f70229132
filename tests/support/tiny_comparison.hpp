#pragma once
// The variants of the small comparisons the compare and shard tests run on the paper's
// random-vibration scenario: the classic datasheet white model, a white model with a random walk
// fitted on the first 60 s, and the oracle (the accelerometer white for the first two).

#include <nlohmann/json.hpp>

namespace stochnav::testing {

inline nlohmann::json tiny_comparison_variants() {
  const nlohmann::json accel = {{"plugin", "white"}, {"params", {{"N", 0.029}}}};
  return {{{"name", "classic"},
           {"noise",
            {{"gyro", {{"plugin", "white"}, {"params", {{"N", 3.33e-5}}}}}, {"accel", accel}}}},
          {{"name", "white_tuned"},
           {"noise",
            {{"gyro",
              {{"plugin", "white"},
               {"params", {{"rate_random_walk", true}}},
               {"fit", {{"end_s", 60}}}}},
             {"accel", accel}}}},
          {{"name", "oracle"},
           {"noise",
            {{"gyro", {{"plugin", "oracle"}, {"params", nlohmann::json::object()}}},
             {"accel", {{"plugin", "oracle"}, {"params", nlohmann::json::object()}}}}}}};
}

/// The static-position aid of the vibration table, without its NIS gate.
inline nlohmann::json static_position_aids() {
  return {
      {{"plugin", "static_position"},
       {"params", {{"sigma_position_m", 0.01}, {"sigma_velocity_mps", 0.3}, {"nis_gate", false}}}}};
}

/// The filter section of the vibration-table runs: their initial sigmas.
inline nlohmann::json vibration_table_filter() {
  return {{"initial_sigma",
           {{"position_m", 0.01},
            {"velocity_m_s", 0.001},
            {"attitude_deg", {0.05, 0.05, 0.5}},
            {"accel_bias_m_s2", 0.001},
            {"gyro_bias_deg_h", 0.7}}}};
}

}  // namespace stochnav::testing

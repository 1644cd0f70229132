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
  return {{{"plugin", "static_position"},
           {"params",
            {{"sigma_position_m", 0.01}, {"sigma_velocity_mps", 0.3}, {"nis_gate", false}}}}};
}

}  // namespace stochnav::testing

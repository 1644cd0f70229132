// The plugin's property tests: the suite every stochnav noise model must pass (installed with
// stochnav), run on this plugin as the build folder holds it.
//   ctest --test-dir build     (or build/second_order_gauss_markov_properties)

#include "stochnav/testing/noise_model_properties.hpp"

namespace {

using stochnav::plugin::SensorGroup;
using stochnav::testing::NoiseModelCase;
using stochnav::testing::NoiseModelProperties;

INSTANTIATE_TEST_SUITE_P(SecondOrderGaussMarkov, NoiseModelProperties,
                         ::testing::Values(NoiseModelCase{"second_order_gauss_markov",
                                                          {{"sigma", 0.5}, {"tau_c", 30}},
                                                          SensorGroup::kGyro,
                                                          {},
                                                          {PLUGIN_DIR}},
                                           NoiseModelCase{"second_order_gauss_markov",
                                                          {{"sigma", {0.01, 0.02, 0.03}},
                                                           {"tau_c", {2, 20, 200}}},
                                                          SensorGroup::kAccel,
                                                          {.times_s = {0.0, 100.0}},
                                                          {PLUGIN_DIR}}),
                         stochnav::testing::noise_model_case_name);

}  // namespace

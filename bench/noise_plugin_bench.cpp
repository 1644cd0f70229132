// Cost of the per-step noise-model calls the filter makes (through the plugin boundary), against
// the filter's budget: 600k epochs/s overall means about 1.7 us per epoch for everything.
// Per epoch and sensor group: white_noise_covariance, bias_walk_covariance, augmented_transition.
// Usage: noise_plugin_bench [epochs]   (default 10,000,000)

#include <fmt/format.h>

#include <Eigen/Core>
#include <cstdlib>
#include <string>

#include "stochnav/plugin/plugin_registry.hpp"
#include "timing.hpp"

int main(int argc, char** argv) {
  namespace sp = stochnav::plugin;
  const long epochs = argc > 1 ? std::atol(argv[1]) : 10'000'000L;
  const sp::PluginRegistry registry({sp::bundled_plugin_dir()});
  struct Case {
    std::string type;
    nlohmann::json params;
  };
  const Case cases[] = {{"white", {{"N", 0.05}, {"K", 0.01}}},
                        {"gauss_markov", {{"sigma", 0.5}, {"tau_c", 100}, {"N", 0.05}}}};
  for (const auto& c : cases) {
    sp::NoiseModelContext context;
    context.params_pointer = "/params";
    const auto model = registry.create_noise_model(c.type, c.params, context, "/plugin");
    const int n = model->augmented_size();
    Eigen::Matrix3d q_white, q_bias;
    Eigen::MatrixXd phi(n, n), q_d(n, n);
    double sink = 0.0;
    const double seconds = stochnav::bench::best_seconds([&] {
      for (long k = 0; k < epochs; ++k) {
        const double t = static_cast<double>(k) * 0.01;
        model->white_noise_covariance(t, 0.01, q_white);
        model->bias_walk_covariance(t, 0.01, q_bias);
        if (n > 0) model->augmented_transition(t, 0.01, phi, q_d);
        sink += q_white(0, 0);
      }
    });
    fmt::print("{:<14} {:6.1f} ns per epoch ({} epochs, {:.3g} M epochs/s) [{}]\n", c.type,
               seconds / static_cast<double>(epochs) * 1e9, epochs,
               static_cast<double>(epochs) / seconds / 1e6, sink > 0 ? "ok" : "?");
  }
  return 0;
}

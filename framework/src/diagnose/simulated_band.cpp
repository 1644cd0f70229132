#include "stochnav/diagnose/simulated_band.hpp"

#include <algorithm>
#include <cmath>

#include "stochnav/sim/noise_generator.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav {

SimulatedBand simulate_band(const NoiseModel& model, std::size_t samples, double rate_hz,
                            std::span<const std::size_t> m, int seeds, std::uint64_t seed) {
  SimulatedBand band;
  band.seeds = seeds;
  const double tau0 = 1.0 / rate_hz;
  for (std::size_t factor : m) band.tau_s.push_back(static_cast<double>(factor) * tau0);
  if (seeds <= 0 || m.empty()) return band;
  std::vector<std::vector<double>> runs;
  const double duration = static_cast<double>(samples) / rate_hz;
  for (int s = 0; s < seeds; ++s) {
    const auto rate =
        simulate_noise(model, duration, rate_hz, seed + static_cast<std::uint64_t>(s));
    const auto phase = phase_from_rate(rate, tau0);
    runs.push_back(deviation_values(Deviation::kOadev, phase, tau0, m));
  }
  std::vector<double> column(runs.size());
  for (std::size_t j = 0; j < m.size(); ++j) {
    for (std::size_t s = 0; s < runs.size(); ++s) column[s] = runs[s][j];
    std::sort(column.begin(), column.end());
    band.low.push_back(column.front());
    band.high.push_back(column.back());
    const std::size_t half = column.size() / 2;
    band.median.push_back(column.size() % 2 == 1 ? column[half]
                                                 : 0.5 * (column[half - 1] + column[half]));
  }
  return band;
}

}  // namespace stochnav

// MTOTDEV, TTOTDEV, HTOTDEV, Theo1, MTIE and TIE rms: their sums normalised as deviation.hpp
// defines them.

#include "extended_estimators.hpp"

#include <cmath>

#include "modified_total_sum.hpp"
#include "theo1_sums.hpp"
#include "time_interval_errors.hpp"

namespace stochnav {
namespace {

double modified_total_deviation(std::span<const double> phase, double tau0_s, std::size_t m) {
  const double tau = static_cast<double>(m) * tau0_s;
  const double subsequences = static_cast<double>(phase.size() + 1 - 3 * m);
  return std::sqrt(modified_total_sum(phase, m) / (2.0 * tau * tau * subsequences));
}

/// At m = 1 Stable32 reports the overlapping Hadamard deviation.
double hadamard_total_deviation(std::span<const double> phase, std::span<const double> frequency,
                                double tau0_s, std::size_t m) {
  if (m == 1) return deviation_value(Deviation::kOhdev, phase, tau0_s, 1);
  const double subsequences = static_cast<double>(frequency.size() + 1 - 3 * m);
  return std::sqrt(modified_total_sum(frequency, m) / (6.0 * subsequences));
}

}  // namespace

bool is_extended_estimator(Deviation kind) {
  switch (kind) {
    case Deviation::kMtotdev:
    case Deviation::kTtotdev:
    case Deviation::kHtotdev:
    case Deviation::kHtotdevNobias:
    case Deviation::kTheo1:
    case Deviation::kTheo1Nobias:
    case Deviation::kMtie:
    case Deviation::kTierms:
      return true;
    default:
      return false;
  }
}

std::vector<double> extended_deviation_values(Deviation kind, std::span<const double> phase,
                                              double tau0_s,
                                              std::span<const std::size_t> m_values) {
  std::vector<double> frequency;
  if (difference_order(kind) == 3) {
    frequency.resize(phase.size() - 1);
    for (std::size_t i = 0; i + 1 < phase.size(); ++i) {
      frequency[i] = (phase[i + 1] - phase[i]) / tau0_s;
    }
  }
  const double theo1_factor = kind == Deviation::kTheo1 ? theo1_bias_factor(phase) : 1.0;
  std::vector<double> values;
  values.reserve(m_values.size());
  for (std::size_t m : m_values) {
    const double tau = static_cast<double>(m) * tau0_s;
    switch (kind) {
      case Deviation::kMtotdev:
        values.push_back(modified_total_deviation(phase, tau0_s, m));
        break;
      case Deviation::kTtotdev:
        values.push_back(tau * modified_total_deviation(phase, tau0_s, m) / std::sqrt(3.0));
        break;
      case Deviation::kHtotdev:
      case Deviation::kHtotdevNobias:
        values.push_back(hadamard_total_deviation(phase, frequency, tau0_s, m));
        break;
      case Deviation::kTheo1:
      case Deviation::kTheo1Nobias:
        values.push_back(std::sqrt(theo1_factor * theo1_variance(phase, tau0_s, m)));
        break;
      case Deviation::kMtie:
        values.push_back(maximum_time_interval_error(phase, m));
        break;
      case Deviation::kTierms: {
        const double count = static_cast<double>(phase.size() - m);
        values.push_back(std::sqrt(time_interval_error_sum(phase, m) / count));
        break;
      }
      default:
        values.push_back(0.0);
        break;
    }
  }
  return values;
}

}  // namespace stochnav

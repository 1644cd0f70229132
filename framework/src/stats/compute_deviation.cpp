// A Stable32-style result table: deviation, noise type, EDF and confidence interval per tau.

#include "fused_passes.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/edf.hpp"
#include "stochnav/stats/noise_id.hpp"

namespace stochnav {

std::vector<DeviationPoint> compute_deviation(Deviation kind, std::span<const double> phase,
                                              double tau0_s, std::span<const std::size_t> m_values,
                                              double confidence) {
  // Every factor's terms checked first: a factor too long for both gives the estimator's error.
  for (std::size_t m : m_values) require_deviation_terms(kind, m, phase.size());
  // The noise types Stable32 identifies (not those it carries over), all together; their pass
  // over the record runs inside the pass of the deviation sums (fused_passes.hpp).
  std::vector<std::size_t> identified_m;
  for (std::size_t k = 0; k < m_values.size(); ++k) {
    if (k == 0 || !keeps_previous_noise_type(kind, m_values[k], phase.size())) {
      identified_m.push_back(m_values[k]);
    }
  }
  NoiseIdentification identification(kind, phase, identified_m);
  const std::vector<double> values =
      deviation_values_alongside(kind, phase, tau0_s, m_values, identification.lag1_job());
  const std::vector<NoiseId> identified = identification.finish();
  std::size_t next_identified = 0;
  std::vector<DeviationPoint> points;
  points.reserve(m_values.size());
  for (std::size_t k = 0; k < m_values.size(); ++k) {
    DeviationPoint point;
    point.m = m_values[k];
    point.tau_s = static_cast<double>(point.m) * tau0_s;
    point.deviation = values[k];
    point.terms = term_count(kind, point.m, phase.size());
    point.alpha = !points.empty() && keeps_previous_noise_type(kind, point.m, phase.size())
                      ? points.back().alpha
                      : identified[next_identified++].alpha;
    point.edf = kind == Deviation::kTotdev ? total_variance_edf(point.alpha, point.m, phase.size())
                                           : greenhall_edf({.alpha = point.alpha,
                                                            .d = difference_order(kind),
                                                            .m = point.m,
                                                            .phase_count = phase.size(),
                                                            .overlapping = is_overlapping(kind),
                                                            .modified = is_modified(kind)});
    const DeviationInterval interval = chi_square_interval(point.deviation, point.edf, confidence);
    point.lower = interval.lower;
    point.upper = interval.upper;
    points.push_back(point);
  }
  return points;
}

}  // namespace stochnav

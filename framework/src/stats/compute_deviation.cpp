// A Stable32-style result table: deviation, noise type, EDF and confidence interval per tau.

#include <algorithm>
#include <cmath>
#include <limits>

#include "fused_passes.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/edf.hpp"
#include "stochnav/stats/noise_id.hpp"
#include "theo1_sums.hpp"

namespace stochnav {
namespace {

/// The estimator whose noise identification Stable32 uses for `kind`: the modified totals
/// identify as MDEV, the Hadamard totals as OHDEV.
Deviation identified_as(Deviation kind) {
  switch (kind) {
    case Deviation::kMtotdev:
    case Deviation::kTtotdev:
      return Deviation::kMdev;
    case Deviation::kHtotdev:
    case Deviation::kHtotdevNobias:
      return Deviation::kOhdev;
    default:
      return kind;
  }
}

/// Stable32's HTOTDEV bias correction factor of the deviation at m > 1 (deviation.hpp).
double hadamard_total_correction(int alpha, std::size_t m) {
  if (m <= 1) return 1.0;
  switch (alpha) {
    case 0:
      return 1.0 / std::sqrt(1.0 - 0.005);
    case -1:
      return 1.0 / std::sqrt(1.0 - 0.149);
    case -2:
      return 1.0 / std::sqrt(1.0 - 0.229);
    default:
      return 1.0;
  }
}

double equivalent_degrees_of_freedom(Deviation kind, int alpha, std::size_t m, std::size_t n) {
  switch (kind) {
    case Deviation::kTotdev:
      return total_variance_edf(alpha, m, n);
    case Deviation::kMtotdev:
    case Deviation::kTtotdev:
      return modified_total_variance_edf(alpha, m, n);
    case Deviation::kTheo1:
    case Deviation::kTheo1Nobias:
    case Deviation::kMtie:
    case Deviation::kTierms:
      return std::numeric_limits<double>::quiet_NaN();
    default: {
      const Deviation as = identified_as(kind);
      return greenhall_edf({.alpha = alpha,
                            .d = difference_order(as),
                            .m = m,
                            .phase_count = n,
                            .overlapping = is_overlapping(as),
                            .modified = is_modified(as)});
    }
  }
}

/// The noise type of a point: identified (or carried over), and those the data leave open.
struct PointNoise {
  int alpha = 0;
  AlphaRange plausible;
};

/// The EDF of a point under `rule`, into point.edf and point.edf_alpha: the identified type's,
/// or the smallest of it and the plausible types' (so never larger than Stable32's). A NaN EDF
/// of the identified type (outside the estimator's domain) stays NaN: no interval, as Stable32.
void set_edf(Deviation kind, const PointNoise& noise, std::size_t phase_count, EdfRule rule,
             DeviationPoint& point) {
  point.edf_alpha = noise.alpha;
  point.edf = equivalent_degrees_of_freedom(kind, noise.alpha, point.m, phase_count);
  if (rule == EdfRule::kStable32) return;
  for (int alpha = noise.plausible.low; alpha <= noise.plausible.high; ++alpha) {
    const double edf = equivalent_degrees_of_freedom(kind, alpha, point.m, phase_count);
    if (edf < point.edf) {
      point.edf = edf;
      point.edf_alpha = alpha;
    }
  }
}

/// Every PM noise (alpha 2, 1) has a variance falling at least as fast as tau^-2 (MVAR tau^-3),
/// every FM noise, Gauss-Markov term and ramp one falling no faster than tau^-1: once an FM
/// type dominates at some tau, no PM type can dominate a longer one. So once the identification
/// at a shorter tau has ruled PM out (its plausible types all FM), a PM type at a longer tau
/// is a slip of the few points left there, and only the FM types of the range stay plausible.
AlphaRange without_phase_noise(AlphaRange plausible) {
  return {std::min(plausible.low, 0), std::min(plausible.high, 0)};
}

/// One result row: the deviation at m with its noise type, EDF and interval.
DeviationPoint make_point(Deviation kind, std::size_t m, double deviation, const PointNoise& noise,
                          std::size_t phase_count, double tau0_s, double confidence,
                          EdfRule rule) {
  DeviationPoint point;
  point.m = m;
  point.tau_s = tau_of(kind, m, tau0_s);
  point.deviation = deviation;
  point.terms = term_count(kind, m, phase_count);
  point.alpha = noise.alpha;
  set_edf(kind, noise, phase_count, rule, point);
  const DeviationInterval interval = chi_square_interval(deviation, point.edf, confidence);
  point.lower = interval.lower;
  point.upper = interval.upper;
  return point;
}

/// Theo1, MTIE, TIE rms: no Stable32 identification per tau. Theo1 takes the nominal noise
/// type of its ThêoBR factor for every row; uncorrected Theo1 and the time-interval errors
/// none (0).
std::vector<DeviationPoint> points_without_identification(Deviation kind,
                                                          std::span<const double> phase,
                                                          double tau0_s,
                                                          std::span<const std::size_t> m_values,
                                                          double confidence) {
  // The ThêoBR factor costs O(N^3): computed once, here, and only for the corrected Theo1.
  const bool corrected_theo1 = kind == Deviation::kTheo1;
  const double bias_factor = corrected_theo1 ? theo1_bias_factor(phase) : 1.0;
  const int alpha = corrected_theo1 ? theo1_bias_noise_type(bias_factor) : 0;
  const Deviation raw_kind = corrected_theo1 ? Deviation::kTheo1Nobias : kind;
  const std::vector<double> values = deviation_values(raw_kind, phase, tau0_s, m_values);
  const double scale = std::sqrt(bias_factor);
  std::vector<DeviationPoint> points;
  points.reserve(m_values.size());
  for (std::size_t k = 0; k < m_values.size(); ++k) {
    points.push_back(make_point(kind, m_values[k], scale * values[k], {alpha, {alpha, alpha}},
                                phase.size(), tau0_s, confidence, EdfRule::kStable32));
  }
  return points;
}

}  // namespace

std::vector<DeviationPoint> compute_deviation(Deviation kind, std::span<const double> phase,
                                              double tau0_s, std::span<const std::size_t> m_values,
                                              double confidence, EdfRule edf_rule) {
  // Every factor's terms checked first: a factor too long for both gives the estimator's error.
  for (std::size_t m : m_values) require_deviation_terms(kind, m, phase.size());
  if (is_theo1(kind) || !has_confidence_interval(kind)) {
    return points_without_identification(kind, phase, tau0_s, m_values, confidence);
  }
  const Deviation identification_kind = identified_as(kind);
  // The noise types Stable32 identifies (not those it carries over), all together; their pass
  // over the record runs inside the pass of the deviation sums (fused_passes.hpp).
  std::vector<std::size_t> identified_m;
  for (std::size_t k = 0; k < m_values.size(); ++k) {
    if (k == 0 || !keeps_previous_noise_type(identification_kind, m_values[k], phase.size())) {
      identified_m.push_back(m_values[k]);
    }
  }
  NoiseIdentification identification(identification_kind, phase, identified_m);
  const std::vector<double> values =
      deviation_values_alongside(kind, phase, tau0_s, m_values, identification.lag1_job());
  const std::vector<NoiseId> identified = identification.finish();
  std::size_t next_identified = 0;
  bool phase_noise_ruled_out = false;  // at a shorter tau: without_phase_noise
  std::vector<DeviationPoint> points;
  points.reserve(m_values.size());
  for (std::size_t k = 0; k < m_values.size(); ++k) {
    const std::size_t m = m_values[k];
    PointNoise noise;
    if (!points.empty() && keeps_previous_noise_type(identification_kind, m, phase.size())) {
      noise.alpha = points.back().alpha;
      const AlphaRange own = plausible_alphas(identification_kind, phase, m);
      noise.plausible = {std::min(own.low, noise.alpha), std::max(own.high, noise.alpha)};
    } else {
      const NoiseId& id = identified[next_identified++];
      noise = {id.alpha, id.plausible};
    }
    if (phase_noise_ruled_out) noise.plausible = without_phase_noise(noise.plausible);
    phase_noise_ruled_out = phase_noise_ruled_out || noise.plausible.high <= 0;
    const double deviation = kind == Deviation::kHtotdev
                                 ? values[k] * hadamard_total_correction(noise.alpha, m)
                                 : values[k];
    points.push_back(
        make_point(kind, m, deviation, noise, phase.size(), tau0_s, confidence, edf_rule));
  }
  return points;
}

}  // namespace stochnav

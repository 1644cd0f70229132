// The wavelet-variance findings after the loop (diagnose_stages.hpp).

#include <vector>

#include "diagnose_stages.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/core/units.hpp"
#include "stochnav/diagnose/effective_model.hpp"
#include "stochnav/fit/gmwm_data.hpp"
#include "stochnav/stats/robust_wavelet_variance.hpp"

namespace stochnav::diagnose_stages {
namespace {

// Levels of a natural-unit record in the record's unit squared (what wv and report.json show).
std::vector<WaveletVariancePoint> in_record_unit(std::vector<WaveletVariancePoint> levels,
                                                 Unit unit) {
  const double si = si_per_unit(unit);
  const double factor = 1.0 / (si * si);
  for (WaveletVariancePoint& level : levels) {
    level.variance *= factor;
    level.lower *= factor;
    level.upper *= factor;
  }
  return levels;
}

// `rate`: natural units. The outlier z-scores are read in natural units, the levels reported in
// the record's.
void check_stochastic_rate(std::span<const double> rate, const Record& record,
                           const DiagnoseOptions& options, DiagnoseResult& result) {
  const std::vector<WaveletVariancePoint> classical =
      in_record_unit(haar_wavelet_variance(rate, record.rate_hz), record.unit);
  const std::vector<WaveletVariancePoint> robust =
      in_record_unit(robust_haar_wavelet_variance(rate, record.rate_hz), record.unit);
  const double si = si_per_unit(record.unit);
  result.wavelet_outliers = check_wavelet_outliers(rate, record.rate_hz, record.start_time_s,
                                                   options.alpha, classical, robust, 1.0 / si);
  result.wavelet_outliers->explained_by_nonstationary =
      find_nonstationary(result.final_assessment().model) != nullptr;
  const bool contaminated = result.wavelet_outliers->contaminated;
  const GmwmData data = gmwm_data_from_levels(contaminated ? robust : classical, record.unit,
                                              record.rate_hz, record.source);
  result.short_tau_gauss_markov = check_short_tau_gauss_markov(
      data, contaminated, result.final_assessment().model, lag1_autocorrelation(rate),
      ShortTauOptions{options.alpha, options.min_term_share});
}

}  // namespace

void check_wavelet_variance(const RecordResiduals& residuals, const TimeDomainWalkTest& walk_test,
                            const DiagnoseOptions& options, DiagnoseResult& result) {
  if (!options.try_wavelet) return;
  const Record& record = residuals.record();
  // 3 scales need 16 samples (wavelet_variance_levels).
  if (residuals.rate().size() < 16) return;
  try {
    if (!walk_test.stochastic_rate().empty()) {
      check_stochastic_rate(walk_test.stochastic_rate(), record, options, result);
    } else if (result.deterministic.empty()) {
      check_stochastic_rate(residuals.rate(), record, options, result);
    } else {
      const std::vector<double> stochastic = residuals.rate_without(result.deterministic);
      check_stochastic_rate(stochastic, record, options, result);
    }
  } catch (const InputError&) {
    // A remainder the wavelet variances refuse (constant): no findings, as for a short record.
    result.wavelet_outliers.reset();
    result.short_tau_gauss_markov.reset();
  }
}

}  // namespace stochnav::diagnose_stages

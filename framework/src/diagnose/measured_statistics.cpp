#include "stochnav/diagnose/measured_statistics.hpp"

#include "stochnav/core/errors.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav {

std::vector<double> natural_rate(const Record& record) {
  const double si = si_per_unit(record.unit);
  std::vector<double> rate;
  if (record.kind == DataKind::kRate) {
    rate.reserve(record.values.size());
    for (double value : record.values) rate.push_back(value * si);
  } else {
    for (std::size_t i = 0; i + 1 < record.values.size(); ++i) {
      rate.push_back((record.values[i + 1] - record.values[i]) * record.rate_hz * si);
    }
  }
  return rate;
}

MeasuredStatistics measure_record(const Record& record, std::size_t windows) {
  MeasuredStatistics measured;
  measured.unit = record.unit;
  measured.rate_hz = record.rate_hz;
  const std::vector<double> phase = record.kind == DataKind::kPhase
                                        ? record.values
                                        : phase_from_rate(record.values, record.tau0());
  measured.samples = phase.size() - 1;
  measured.duration_s = static_cast<double>(measured.samples) / record.rate_hz;
  const auto octave_m =
      averaging_factors(Deviation::kOadev, TauSpacing::kOctave, phase.size(), record.tau0());
  if (octave_m.size() < 4) {
    throw InputError(record.source + ": " + std::to_string(measured.samples) +
                     " samples are too few to diagnose (fewer than 4 octave taus); use a record "
                     "of at least 64 samples");
  }
  const auto dense_m =
      averaging_factors(Deviation::kOadev, TauSpacing::kDense, phase.size(), record.tau0());
  measured.octave = compute_deviation(Deviation::kOadev, phase, record.tau0(), octave_m);
  measured.dense = compute_deviation(Deviation::kOadev, phase, record.tau0(), dense_m);

  const double si = si_per_unit(record.unit);
  AvarMeasurement& octave = measured.octave_avar;
  octave.phase_count = phase.size();
  octave.tau0_s = record.tau0();
  for (const auto& point : measured.octave) {
    if (!(point.deviation > 0.0)) continue;  // a constant stretch: nothing to compare
    octave.m.push_back(point.m);
    octave.tau_s.push_back(point.tau_s);
    octave.avar.push_back(point.deviation * si * point.deviation * si);
  }
  if (octave.m.size() < 4) {
    throw InputError(record.source +
                     ": the record's Allan deviation is zero at most taus "
                     "(constant samples?); diagnose needs a noisy record");
  }
  measured.dense_fit =
      fit_data_from_deviations(Deviation::kOadev, measured.dense, record.unit, record.rate_hz);
  // Candidate fits weigh the dense points by their Greenhall edf as independent points: the
  // model-weighted passes would recompute the estimator covariance of ~50 points per
  // candidate, and the gap (which decides) uses the exact covariance anyway.
  measured.dense_fit.phase_count = 0;
  measured.windows = window_variances(natural_rate(record), record.rate_hz, windows);
  return measured;
}

}  // namespace stochnav

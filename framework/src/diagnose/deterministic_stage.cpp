// Stage 2 of diagnose(): deterministic effects, found in the time domain and removed from the
// record (diagnose_stages.hpp).
#include <fmt/format.h>

#include "diagnose_stages.hpp"

namespace stochnav::diagnose_stages {

std::vector<DeterministicFinding> find_record_effects(const RecordResiduals& residuals,
                                                      const NoiseModel& stochastic,
                                                      const DiagnoseResult& result,
                                                      const DiagnoseOptions& options) {
  if (!options.try_deterministic) return {};
  DeterministicOptions deterministic_options;
  deterministic_options.alpha = options.alpha;
  return find_deterministic_effects(residuals.rate_without(result.deterministic),
                                    residuals.record().rate_hz, stochastic, residuals.aux_rate(),
                                    deterministic_options);
}

void accept_deterministic_findings(const std::vector<DeterministicFinding>& findings,
                                   const RecordResiduals& residuals, const NoiseModel& stochastic,
                                   const DiagnoseOptions& options, DiagnoseResult& result) {
  double previous_gap = result.initial.gap.value;
  std::vector<NoiseTerm> removed = result.deterministic;
  for (const DeterministicFinding& finding : findings) {
    removed.push_back(finding.term);
    MeasuredStatistics measured_after =
        measure_record(residuals.record_without(removed), options.windows);
    ModelAssessment after = assess_model(stochastic, measured_after, options);
    if (after.gap.value > previous_gap) break;  // never a term that widens the gap
    DiagnoseIteration step;
    step.effect = term_type(finding.term);
    step.added_term = finding.term;
    step.added_term_sigma = finding.sigma;
    step.time_range_s = finding.time_range_s;
    step.gap_before = previous_gap;
    step.gap_after = after.gap.value;
    step.evidence =
        finding.evidence + fmt::format(" Removed from the record: gap {:.3g} -> {:.3g}. Added: {}.",
                                       step.gap_before, step.gap_after,
                                       describe_term_short(finding.term, residuals.record().unit));
    step.after = std::move(after);
    previous_gap = step.gap_after;
    result.iterations.push_back(std::move(step));
    result.deterministic.push_back(finding.term);
    result.measured = std::move(measured_after);
  }
}

}  // namespace stochnav::diagnose_stages

// Helpers the stages of diagnose() share (diagnose_stages.hpp).
#include <algorithm>
#include <variant>

#include "diagnose_stages.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav::diagnose_stages {

std::vector<std::size_t> band_factors(const MeasuredStatistics& measured) {
  std::vector<std::size_t> m;
  for (const auto& point : measured.dense) m.push_back(point.m);
  for (const auto& point : measured.octave) m.push_back(point.m);
  std::sort(m.begin(), m.end());
  m.erase(std::unique(m.begin(), m.end()), m.end());
  return m;
}

ModelAssessment assessment_with_band(const NoiseModel& model, const Gap& gap,
                                     const MeasuredStatistics& measured,
                                     const DiagnoseOptions& options) {
  ModelAssessment assessment;
  assessment.model = model;
  assessment.gap = gap;
  if (options.seeds > 0) {
    assessment.band = simulate_band(model, measured.samples, measured.rate_hz,
                                    band_factors(measured), options.seeds, options.seed);
  }
  return assessment;
}

std::size_t added_parameters(const NoiseTerm& term) {
  if (const auto* nonstationary = std::get_if<NonstationaryTerm>(&term)) {
    return 3 * nonstationary->segments.size();
  }
  return term_type(term) == TermType::kGaussMarkov || term_type(term) == TermType::kSinusoid ? 2
                                                                                             : 1;
}

double total_parameters(const NoiseModel& model) {
  std::size_t p = 0;
  for (const NoiseTerm& term : model.terms) p += added_parameters(term);
  return static_cast<double>(p);
}

bool has_type(const NoiseModel& model, TermType type) {
  return std::any_of(model.terms.begin(), model.terms.end(),
                     [&](const NoiseTerm& term) { return term_type(term) == type; });
}

bool repeatable(TermType type) {
  return type == TermType::kGaussMarkov || type == TermType::kSinusoid;
}

std::string describe_term_short(const NoiseTerm& term, Unit unit) {
  std::string text = describe(term, quantity_of(unit));
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

Signature signature_of(const Gap& gap, const NoiseModel& model,
                       const MeasuredStatistics& measured) {
  return read_signature(gap.avar, measured.dense_fit.tau_s, measured.dense_fit.avar,
                        measured.dense_fit.edf, model);
}

}  // namespace stochnav::diagnose_stages

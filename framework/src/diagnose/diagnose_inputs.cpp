// Stage 1 of diagnose(): the inputs checked, the model split, the record as the stages read it
// (diagnose_stages.hpp).
#include <fmt/format.h>

#include "diagnose_stages.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav::diagnose_stages {

void check_diagnose_inputs(const Record& record, const NoiseModel& model,
                           const DiagnoseOptions& options) {
  if (const auto problem = options.validate(); !problem.empty()) {
    throw ConfigError("diagnose: " + problem);
  }
  if (const auto issue = find_model_issue(model)) {
    throw ConfigError(issue->pointer + ": " + issue->problem + "; expected " + issue->expected);
  }
  if (quantity_of(model.unit) != quantity_of(record.unit)) {
    throw ConfigError("diagnose: the model is in " + unit_name(model.unit) + " but the record in " +
                      unit_name(record.unit) + "; pass a matching --unit");
  }
}

SplitModel split_model(const NoiseModel& model) {
  SplitModel split{{model.unit, model.rate_hz, {}}, {}};
  for (const NoiseTerm& term : model.terms) {
    if (is_deterministic(term_type(term))) {
      split.deterministic.push_back(term);
    } else {
      split.stochastic.terms.push_back(term);
    }
  }
  return split;
}

RecordResiduals::RecordResiduals(const Record& record, const std::vector<AuxChannel>& aux)
    : record_(record), rate_(natural_rate(record)) {
  for (const AuxChannel& channel : aux) {
    if (channel.values.size() < rate_.size()) {
      throw ConfigError(fmt::format("diagnose: aux column \"{}\" has {} values for {} samples",
                                    channel.name, channel.values.size(), rate_.size()));
    }
    aux_rate_.push_back({channel.name,
                         {channel.values.begin(),
                          channel.values.begin() + static_cast<std::ptrdiff_t>(rate_.size())}});
  }
}

std::vector<double> RecordResiduals::rate_without(const std::vector<NoiseTerm>& terms) const {
  return remove_deterministic(rate_, record_.rate_hz, terms, aux_rate_);
}

Record RecordResiduals::record_without(const std::vector<NoiseTerm>& terms) const {
  Record residual = record_;
  residual.kind = DataKind::kRate;
  residual.values = rate_without(terms);
  const double si = si_per_unit(record_.unit);
  for (double& value : residual.values) value /= si;
  return residual;
}

TimeDomainWalkTest::TimeDomainWalkTest(const RecordResiduals& residuals,
                                       const std::vector<NoiseTerm>& deterministic,
                                       const DiagnoseOptions& options)
    : enabled_(options.try_time_domain_walk),
      alpha_(options.alpha),
      rate_hz_(residuals.record().rate_hz),
      stochastic_rate_(enabled_ ? residuals.rate_without(deterministic) : std::vector<double>{}) {}

RandomWalkTest TimeDomainWalkTest::operator()(const NoiseModel& model) const {
  if (!enabled_) return RandomWalkTest{};
  try {
    return test_rate_random_walk(stochastic_rate_, rate_hz_, model, alpha_);
  } catch (const ConfigError&) {
    return RandomWalkTest{};  // a record too short for blocks: the test is not run
  }
}

}  // namespace stochnav::diagnose_stages

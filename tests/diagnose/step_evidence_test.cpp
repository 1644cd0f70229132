// Issue #26 item 10: the evidence of a stochastic step compares the kept term's gap (the exact
// one) only with gaps assessed the same way, never with a candidate's screening gap ("-> 3.09e+04
// (next best: ... at 12.5)"), and flags a term whose fit ended on a search bound.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "diagnose_stages.hpp"

namespace stochnav::diagnose_stages {
namespace {

Trial kept_gauss_markov(std::vector<std::string> at_bound) {
  Trial kept;
  kept.outcome.type = TermType::kGaussMarkov;
  kept.outcome.usable = true;
  kept.outcome.exact = true;
  kept.outcome.gap = 30900.0;
  kept.outcome.at_bound = std::move(at_bound);
  kept.gap.value = 30900.0;
  return kept;
}

CandidateOutcome sinusoid(double gap, bool exact) {
  CandidateOutcome outcome;
  outcome.type = TermType::kSinusoid;
  outcome.usable = true;
  outcome.gap = gap;
  outcome.exact = exact;
  return outcome;
}

std::string evidence(const Trial& kept, const std::vector<CandidateOutcome>& outcomes) {
  Gap before;
  before.value = 50000.0;
  return evidence_text(Signature{}, before, kept, outcomes, std::nullopt, Unit::kDegPerHour);
}

TEST(StepEvidence, AScreeningGapIsNotComparedWithTheExactOne) {
  const Trial kept = kept_gauss_markov({});
  const std::string text = evidence(kept, {kept.outcome, sinusoid(12.5, false)});
  EXPECT_EQ(text.find("12.5"), std::string::npos) << text;
  EXPECT_NE(text.find("5e+04 -> 3.09e+04 (no other candidate was assessed exactly)"),
            std::string::npos)
      << text;
}

TEST(StepEvidence, TheRunnerUpAssessedTheSameWayIsNamed) {
  const Trial kept = kept_gauss_markov({});
  const std::string text =
      evidence(kept, {kept.outcome, sinusoid(12.5, false), sinusoid(41000.0, true)});
  EXPECT_NE(text.find("(next best, assessed the same way: sinusoid at 4.1e+04)"),
            std::string::npos)
      << text;
}

TEST(StepEvidence, ATermOnItsSearchBoundIsFlagged) {
  const Trial kept = kept_gauss_markov({"gauss_markov.tau_c"});
  const std::string text = evidence(kept, {kept.outcome});
  EXPECT_NE(text.find("Flagged: gauss_markov.tau_c ended on the search bound of the fit"),
            std::string::npos)
      << text;
  EXPECT_EQ(evidence(kept_gauss_markov({}), {}).find("Flagged"), std::string::npos);
}

}  // namespace
}  // namespace stochnav::diagnose_stages

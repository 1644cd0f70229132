#pragma once
// `diagnose --run --aux COLUMN`: do a filter's normalised innovations drift with an auxiliary
// channel of the run (a column of the recording's aids.csv, e.g. temperature)?
//
// Method, per aid component: u = z / sqrt(S_ii) over the accepted updates; u and the channel
// (linearly interpolated to the update times) averaged over B = min(32, n / 4) consecutive
// blocks of equal count; ordinary least squares of the block means of u on [1, channel]. The
// slope's t statistic uses the residual scale with the effective number of blocks
// B (1 - r1) / (1 + r1), r1 the lag-1 autocorrelation of the residuals (innovations of static
// aids are strongly correlated). A finding when the two-sided p-value is below alpha divided by
// the number of (component, channel) pairs (Bonferroni). The evidence also gives the slope's t
// with the time added as a regressor: a channel that rises with time cannot be told from a
// plain drift, and the report says so.

#include <string>
#include <vector>

#include "stochnav/diagnose/innovation_analysis.hpp"

namespace stochnav {

/// A channel sampled on a time grid: values[k] at t0_s + k / rate_hz.
struct TimedChannel {
  std::string name;
  double t0_s = 0.0;
  double rate_hz = 1.0;
  std::vector<double> values;
};

struct InnovationAuxFinding {
  int aid_index = 0;
  std::string aid_type;
  std::string component;  ///< component name, e.g. "position E (m)"
  std::string column;     ///< the channel
  double slope = 0.0;        ///< change of the normalised innovation per unit of the channel
  double slope_sigma = 0.0;  ///< its 1-sigma uncertainty
  double t_statistic = 0.0;
  double p_value = 1.0;
  double t_with_time = 0.0;  ///< the slope's t with time as a second regressor
  std::string evidence;      ///< one sentence with the numbers
};

/// Tests every component of every aid against every channel (see the file comment).
/// `analysis` gives the component names (analyse_innovations of the same innovations).
std::vector<InnovationAuxFinding> innovation_aux_findings(
    const std::vector<AidInnovations>& innovations, const InnovationAnalysis& analysis,
    const std::vector<TimedChannel>& channels, double alpha);

}  // namespace stochnav

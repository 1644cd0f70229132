#pragma once
// Every run checks itself against its own uncertainty.
//
// With truth, at each scored (output) epoch: the share of epochs at which each error metric
// (experiment/navigation_errors.hpp) lies inside the filter's 3-sigma of it, and the mean NEES of
// the nine position / velocity / attitude error states (chi-square with 9 dof: mean 9 when the
// filter is consistent). A metric inside its 3-sigma on fewer than kConsistentShare of the
// epochs makes the run OPTIMISTIC: its covariance claims more than it delivers.
//
// With or without truth, per aid: the number of update attempts, the share rejected by the NIS
// gate (or with a singular S), the mean NIS of the accepted updates against its degrees of
// freedom (the measurement size: a consistent filter's mean NIS equals it), and the share of
// innovation components (of every attempt, rejected ones included) inside 3 sqrt(S_ii). An aid
// rejected more than kRejectionWarningShare of the time is flagged: either it or the filter's
// noise model is wrong.
//
// Without truth (a user's own recording) the innovations are the run's only check of itself:
// an aid whose innovation components are inside their 3 sigma on fewer than kConsistentShare of
// the attempts makes the run OPTIMISTIC (the filter predicts the aids better than it does). The
// check cannot see an error the aids do not observe (a heading error under position-only aids).
//
// Costs a few additions per epoch; used by `stochnav run` (metrics.json) and reusable by compare.

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "stochnav/experiment/navigation_errors.hpp"
#include "stochnav/filter/mwd_navigator.hpp"

namespace stochnav {

inline constexpr double kConsistentShare = 0.95;        ///< inside 3-sigma at least this often
inline constexpr double kRejectionWarningShare = 0.05;  ///< an aid rejected more often is flagged

/// Update statistics of one aid.
struct AidStatistics {
  std::string type;            ///< the aid's plugin type
  int dof = 0;                 ///< measurement size
  std::uint64_t attempts = 0;  ///< update attempts
  std::uint64_t rejected = 0;  ///< gate rejections and singular S
  double nis_sum = 0.0;        ///< sum of the accepted updates' NIS
  std::uint64_t components = 0;         ///< innovation components with a finite z and sigma
  std::uint64_t components_inside = 0;  ///< of them, |z| <= 3 sigma
  double rejected_share() const {
    return attempts > 0 ? static_cast<double>(rejected) / static_cast<double>(attempts) : 0.0;
  }
  /// Mean NIS of the accepted updates (NaN when there is none).
  double nis_mean() const;
  /// Share of innovation components inside 3 sigma (NaN when there is none).
  double inside_3sigma() const;
};

class RunConsistency final {
 public:
  /// `aid_types` and `aid_dofs`: type and measurement size of each aid, in the run's order.
  RunConsistency(const std::vector<std::string>& aid_types, const std::vector<int>& aid_dofs);

  /// One scored epoch: the errors, the filter's 1-sigma of each (NaN entries are skipped), and
  /// the NEES of the nine pos/vel/att error states (NaN skipped).
  void add_epoch(const std::array<double, kErrorMetricCount>& errors,
                 const std::array<double, kErrorMetricCount>& sigma, double nees);
  /// The update attempts of one step (MwdNavigator::innovations()).
  void add_innovations(std::span<const InnovationRecord> records);

  bool has_truth() const { return nees_count_ > 0 || scored_[0] > 0; }
  /// Share of scored epochs with |error| <= 3 sigma (NaN when never scored).
  double inside_3sigma(std::size_t metric) const;
  double nees_mean() const;  ///< NaN when never scored
  std::uint64_t nees_samples() const { return nees_count_; }  ///< epochs with a NEES
  const std::vector<AidStatistics>& aids() const { return aids_; }
  /// Accepted updates of every aid together.
  std::uint64_t accepted_updates() const;

  /// {"inside_3sigma": {metric: share}, "nees_mean": x, "nees_dof": 9, "nees_samples": N}, or
  /// null without truth.
  nlohmann::json consistency_json() const;
  /// [{"type", "dof", "attempts", "rejected_share", "nis_mean", "inside_3sigma"}] per aid.
  nlohmann::json aids_json() const;
  /// The run's verdict on itself: {"source": "truth" | "innovations" | "none", "optimistic":
  /// bool, "reason": "" or what failed}; from truth when the run has it, else from the aids'
  /// innovations ("none": neither truth nor aid updates).
  nlohmann::json self_check_json() const;
  /// With truth: "consistency: ok (NEES mean ...)" or "consistency: OPTIMISTIC (lat_err_m
  /// inside 3-sigma only 41 % of epochs)" (the worst metric). Without: "consistency
  /// (innovations, no truth): ok (...)" or "... OPTIMISTIC (rop innovations inside 3-sigma only
  /// 80 % of 3000 components)"; empty without truth and aid updates.
  std::string consistency_line() const;
  /// One warning line per aid rejected more than kRejectionWarningShare of the time, and one
  /// per aid that never had an update accepted (its data never reached the filter).
  std::vector<std::string> aid_warnings() const;

 private:
  std::array<std::uint64_t, kErrorMetricCount> scored_{};
  std::array<std::uint64_t, kErrorMetricCount> inside_{};
  double nees_sum_ = 0.0;
  std::uint64_t nees_count_ = 0;
  std::vector<AidStatistics> aids_;

  /// The truth-based worst metric (kErrorMetricCount when none is below kConsistentShare).
  std::size_t worst_metric() const;
  /// The aid with the smallest innovation share below kConsistentShare, or aids_.size().
  std::size_t worst_aid() const;
};

}  // namespace stochnav

#pragma once
// The gap between a noise model and a measured record: how far the record's overlapping Allan
// variance lies from what records of the model give, in units of the estimator's own scatter.
//
// Definition (DESIGN.md, "The discrepancy workflow", step 3). At the octave averaging factors
// m_i (tau_i = m_i tau0, i = 1..M; Stable32's octave set, up to N/4) let A_i be the measured
// OADEV variance and, under the model (its stationary equivalent, diagnose/effective_model.hpp),
// mu_i its closed-form expectation and V_ij the exact covariance of the estimates of a record of
// the same length (fit/oadev_covariance.hpp, Gaussian terms; times kappa for a nonstationary
// model). With nu_i = 2 mu_i^2 / V_ii the estimate's equivalent degrees of freedom,
//   z_i = [ln A_i - ln mu_i - b(nu_i)] / s(nu_i),
//   b(nu) = digamma(nu/2) - ln(nu/2),  s(nu)^2 = trigamma(nu/2)
// (the mean and standard deviation of ln(chi2(nu)/nu)), so each z_i is about N(0, 1) when the
// model is right. The AVAR gap is the reduced chi-square
//   G_avar = (1/M) sum z_i^2.
// Neighbouring octave estimates are correlated (R_ij = V_ij / sqrt(V_ii V_jj), about 0.5), which
// does not bias G_avar (E G_avar = 1) but widens its spread; by Satterthwaite's approximation
// M G_avar ~ c chi2(nu_avar) with c = tr(R^2) / M, i.e. G_avar ~ chi2(nu_avar) / nu_avar with the
// effective degrees of freedom nu_avar = M^2 / tr(R^2) (< M).
//
// The stationarity part (diagnose/stationarity.hpp) gives G_stat ~ chi2(nu_stat) / nu_stat,
// nu_stat = windows - 1. The gap is the larger of the two reduced chi-squares,
//   gap = max(G_avar, G_stat),
// about 1 for a consistent model (each part has mean 1 and spread sqrt(2 / nu)), large when
// either the Allan variance or the windows disagree. Testing the parts separately keeps a
// strong discrepancy in one from being diluted by the other's degrees of freedom. The model is
// consistent when each part is below the (1 - alpha/2) quantile of its chi2(nu)/nu (Bonferroni:
// false-alarm probability <= alpha, 1e-3 by default). Their pooled chi-square
// nu_avar G_avar + nu_stat G_stat (on nu_avar + nu_stat dof) measures how much a candidate term
// explains. Scale-free: nothing changes when the record and the model are rescaled together.
//
// Deterministic sinusoids add to mu_i but not to V (their AVAR estimate hardly scatters), and
// nu_i is capped at 2 n_i (n_i terms of the estimator) so a model that is all sinusoid still has
// a finite scatter.

#include <cstddef>
#include <span>
#include <vector>

#include "stochnav/diagnose/stationarity.hpp"
#include "stochnav/model/noise_model.hpp"

namespace stochnav {

/// The measured overlapping Allan variances the gap compares against (natural units).
struct AvarMeasurement {
  std::vector<std::size_t> m;   ///< averaging factors, ascending
  std::vector<double> tau_s;    ///< m * tau0 (s)
  std::vector<double> avar;     ///< measured OADEV variance, natural units^2, > 0
  std::size_t phase_count = 0;  ///< phase points of the record (samples + 1)
  double tau0_s = 0.0;          ///< sampling interval (s)
};

struct AvarGapPoint {
  double tau_s = 0.0;
  double avar_measured = 0.0;  ///< natural units^2
  double avar_model = 0.0;     ///< mu_i, natural units^2
  double edf_model = 0.0;      ///< nu_i
  double z = 0.0;              ///< standardized log residual
};

struct AvarGap {
  std::vector<AvarGapPoint> points;
  double reduced_chi_square = 0.0;  ///< G_avar
  double effective_dof = 0.0;       ///< nu_avar
};

/// G_avar of `model` against `measured` (see the file comment). Throws ConfigError when the
/// model's Allan variance is not > 0 at a measured tau.
AvarGap avar_gap(const NoiseModel& model, const AvarMeasurement& measured);

/// A quick G_avar for screening candidates: `model`'s closed form against `measured` with the
/// degrees of freedom and effective dof of `reference` (a gap of a nearby model at the same
/// points) instead of a new covariance. Exact when the model's relative estimator scatter is
/// the reference's; the candidates that screen best are then assessed exactly.
AvarGap screening_avar_gap(const NoiseModel& model, const AvarMeasurement& measured,
                           const AvarGap& reference);

struct Gap {
  AvarGap avar;
  StationarityTest stationarity;
  double value = 0.0;                   ///< the gap: max(G_avar, G_stat)
  double chi_square = 0.0;              ///< pooled: nu_avar G_avar + nu_stat G_stat
  double dof = 0.0;                     ///< nu_avar + nu_stat
  double avar_threshold = 0.0;          ///< chi2 quantile (1 - alpha/2, nu_avar) / nu_avar
  double stationarity_threshold = 0.0;  ///< the same for nu_stat (1 without windows)
  bool consistent = false;              ///< both parts below their thresholds
};

/// Combines the two parts. alpha in (0, 1): the false-alarm probability of `consistent`.
Gap combine_gap(AvarGap avar, StationarityTest stationarity, double alpha);

}  // namespace stochnav

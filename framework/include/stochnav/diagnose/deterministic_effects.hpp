#pragma once
// Deterministic effects in the time domain: a rate ramp, a bias step at an unknown time, a bias
// linear in an auxiliary channel (temperature). diagnose finds them here, removes them from the
// record and diagnoses the stochastic remainder with the Allan variance as before.
//
// Method. The record's rate is cut into M blocks of length T; y_j are the block means and
// d_j = y_{j+1} - y_j their first differences (M - 1 values). d is a second difference of the
// phase, so its covariance under the stochastic model follows exactly from the generalized phase
// covariance G of every term (as in fit/oadev_covariance.hpp; a sinusoid of random phase adds
// A^2 cos(w h) / (2 w^2)):
//   Cov(d_i, d_j) = sum_{p,q in 0..2} a_p a_q G((i - j + p - q) T) / T^2,  a = (1, -2, 1).
// The stochastic alternatives: the model's covariance S0 with a free scale s^2 (a mis-set
// white level, profiled out), with or without a free rate random walk k (covariance
// S0 + k S_K, k profiled on a grid), so a wandering bias is weighed against a drift. Each
// deterministic effect is a column of the GLS design X (d = X b + e):
//   rate_ramp        d_j = R T                        (a constant)
//   aux_sensitivity  d_j = c (a_{j+1} - a_j)           (a: block means of the channel)
//   bias_step        d_j = s (f_{j+1}(t) - f_j(t))     (f_j: part of block j after t)
// Selection by information criterion: every alternative scores -2 ln L plus a price: the
// random walk chi2_1(1 - alpha); a ramp the same; an aux column chi2_1(1 - alpha / #columns)
// (Bonferroni); a step, whose time is the maximum of a two-segment likelihood ratio scanned
// over 4 M positions, chi2_1(1 - alpha / (4 M)) (Bonferroni over the scan, conservative as the
// scanned statistics are correlated). A deterministic candidate (with or without the random
// walk) is taken when it scores best of all and its likelihood ratio against the same
// stochastic alternative exceeds its price; then all columns are refitted jointly and the next
// round starts; stop when a stochastic alternative scores best. The step time is refined on a
// grid of T/64 and its 1-sigma interval read off the profile likelihood (ratio within 1 of its
// maximum). Coefficient uncertainties: the GLS covariance with the residual scale.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "stochnav/model/noise_model.hpp"

namespace stochnav {

/// An auxiliary channel of the record (a CSV column), sampled with the rate samples.
struct AuxChannel {
  std::string name;            ///< column name
  std::vector<double> values;  ///< one per rate sample, the channel's own unit
};

struct DeterministicOptions {
  std::size_t max_blocks = 128;  ///< M, the block count (fewer on short records: >= 16 samples)
  double alpha = 1e-3;           ///< false-alarm probability per effect type
  bool try_ramp = true;
  bool try_step = true;
};

/// One effect found, with its fitted parameters.
struct DeterministicFinding {
  NoiseTerm term;  ///< rate_ramp, bias_step or aux_sensitivity, natural units
  /// 1-sigma uncertainties of the term's parameters, by JSON name, natural units.
  std::vector<std::pair<std::string, double>> sigma;
  double statistic = 0.0;  ///< likelihood ratio when it was selected
  double threshold = 0.0;  ///< its critical value
  double random_walk_share = 0.0;  ///< profiled k: rate random walk variance over the model's
  std::optional<std::array<double, 2>> time_range_s;  ///< step: its 1-sigma time interval
  std::string evidence;                               ///< one sentence, numbers included
};

/// Finds the deterministic effects in `rate` (natural units, rate_hz) against the stochastic
/// model `model` (deterministic terms of the model are ignored; remove them first). Findings in
/// order of selection; parameters are from the final joint fit. Throws ConfigError for a
/// record shorter than 16 blocks of 16 samples or an aux channel of another length.
std::vector<DeterministicFinding> find_deterministic_effects(
    const std::vector<double>& rate, double rate_hz, const NoiseModel& model,
    const std::vector<AuxChannel>& aux, const DeterministicOptions& options = {});

/// The time-domain test for a rate random walk the model lacks (or understates): the block
/// differences above under `model` with a free white scale s^2 (covariance s^2 S0) against
/// the same with a free rate random walk (s^2 (S0 + k S_K), k >= 0 profiled on the grid), a
/// likelihood ratio against chi2_1 at 1 - alpha (conservative: k = 0 is on the boundary, so the
/// false-alarm probability is about alpha / 2). Far more powerful at the long taus than the
/// Allan variance, whose last octaves have few degrees of freedom each. Deterministic terms of
/// `model` are ignored (remove them from `rate` first). Throws ConfigError as
/// find_deterministic_effects for a record too short.
struct RandomWalkTest {
  double statistic = 0.0;    ///< -2 ln L ratio, >= 0
  double threshold = 0.0;    ///< chi2_1 quantile at 1 - alpha
  double k = 0.0;            ///< the profiled K, natural units (signal / sqrt(s)); 0: none
  double white_scale = 1.0;  ///< the profiled s^2 with the random walk
  /// -2 ln L of the block differences under the model with its free white scale (up to a
  /// constant common to all models of the same record): compares models in the time domain.
  double minus_two_log_l = 0.0;
  bool significant = false;  ///< statistic > threshold
  std::size_t blocks = 0;    ///< M
  double block_s = 0.0;      ///< T (s)
};
RandomWalkTest test_rate_random_walk(const std::vector<double>& rate, double rate_hz,
                                     const NoiseModel& model, double alpha,
                                     std::size_t max_blocks = 128);

/// rate minus the deterministic terms (rate_ramp, bias_step, aux_sensitivity) among `terms`,
/// sample k at record time (k + 1/2) / rate_hz as the simulator writes them. Throws ConfigError
/// when an aux_sensitivity term's column is not among `aux`.
std::vector<double> remove_deterministic(const std::vector<double>& rate, double rate_hz,
                                         const std::vector<NoiseTerm>& terms,
                                         const std::vector<AuxChannel>& aux);

}  // namespace stochnav

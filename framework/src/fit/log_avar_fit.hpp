#pragma once
// One Ceres solve of the log-domain Allan-variance fit for a fixed list of terms (the method is
// described in fit/fit_noise_terms.hpp). Internal to the fit domain.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "stochnav/fit/fit_data.hpp"
#include "stochnav/fit/fit_noise_terms.hpp"
#include "stochnav/fit/slope_readoffs.hpp"
#include "stochnav/model/noise_term.hpp"

namespace stochnav::fit_detail {

/// No slot: a term of the automatic selection, which cannot be steered.
inline constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);

/// A term and the natural logs of its parameters (see parameter_count), fixed ones included.
struct TermParameters {
  TermType type = TermType::kAngleRandomWalk;
  std::vector<double> log_values;
  /// Index of the term in FitOptions::terms, whose controls steer it; kNoSlot: none.
  std::size_t slot = kNoSlot;
};

struct Solution {
  std::vector<TermParameters> terms;
  double cost = 0.0;        ///< 1/2 sum rho(r_i^2)
  double chi_square = 0.0;  ///< sum r_i^2
  int iterations = 0;
  bool converged = false;
  bool usable = false;      ///< Ceres returned a usable point
  std::size_t parameter_count = 0;  ///< free (fitted) parameters, fixed ones not counted
};

/// Parameters fitted for a term type: 1, or 2 for Gauss-Markov (sigma, tau_c) and sinusoid
/// (amplitude, frequency). 0 for nonstationary (not fittable).
std::size_t parameter_count(TermType type);

class LogAvarFit {
 public:
  /// Residual scales and bias corrections from `edf` (one per point; it replaces data.edf).
  /// `correlation`: correlation matrix of the estimates (empty: independent), used only for
  /// the uncertainties.
  LogAvarFit(const FitData& data, const FitOptions& options, std::span<const double> edf,
             Eigen::MatrixXd correlation = {});

  /// Minimises the cost from `start` (clamped into the bounds; fixed parameters set to their
  /// values and held).
  Solution solve(std::vector<TermParameters> start) const;

  /// Covariance of all log parameters of `solution` (term order): ceres::Covariance at the
  /// solution, C = (J^T J)^-1, or with a correlation matrix R the sandwich C J^T R J C.
  /// Entries of parameters at a search bound, or all when Ceres fails, are NaN; of fixed
  /// parameters 0.
  Eigen::MatrixXd covariance(const Solution& solution) const;

  /// Whether parameter k of `term` sits at (within 1e-6 of) an edge of its default search
  /// range (a failed parameter). Fixed parameters and bounds the user gave never are.
  bool at_bound(const TermParameters& term, std::size_t k) const;
  /// Whether parameter k of `term` sits on a bound the user gave (FitOptions::controls).
  bool on_given_bound(const TermParameters& term, std::size_t k) const;
  /// Whether parameter k of `term` is held at a value the user gave.
  bool is_fixed(const TermParameters& term, std::size_t k) const;
  /// The control of parameter k of `term` (FitOptions::controls), or nullptr.
  const ParameterControl* control(const TermParameters& term, std::size_t k) const;

  /// Starting log parameters for a term of `type` added to a model, steered by the controls
  /// of FitOptions::terms[slot] (their start and fixed values replace the searched ones).
  std::vector<std::vector<double>> starts(TermType type, std::size_t slot = kNoSlot) const;

  std::size_t point_count() const { return tau_.size(); }
  const SlopeReadoffs& readoffs() const { return readoffs_; }

 private:
  /// The starts of a term of `type` from the data alone (fit_noise_terms.hpp, "Starting values").
  std::vector<std::vector<double>> searched_starts(TermType type) const;
  /// Sinusoid starts {log A, log f} from a scan of the log misfit over frequency.
  std::vector<std::vector<double>> sinusoid_frequency_scan() const;
  /// The default search range of parameter k of a term of `type`, natural logs.
  double lower_bound(TermType type, std::size_t k) const;
  double upper_bound(TermType type, std::size_t k) const;
  /// The search range of parameter k of `term`: the bound given for it, else the default.
  double lower_bound(const TermParameters& term, std::size_t k) const;
  double upper_bound(const TermParameters& term, std::size_t k) const;

  std::vector<double> tau_;
  std::vector<double> avar_;
  std::vector<double> target_;     // log avar_i - b_i
  std::vector<double> inv_sigma_;  // 1 / s_i
  std::vector<double> background_;  // AVAR of the held terms (FitOptions::fixed_terms) at tau_i
  Eigen::MatrixXd correlation_;
  FitOptions options_;
  SlopeReadoffs readoffs_;
  double log_root_avar_min_ = 0.0;
  double log_root_avar_max_ = 0.0;
  double tau_min_ = 0.0;
  double tau_max_ = 0.0;
};

}  // namespace stochnav::fit_detail

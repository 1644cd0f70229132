#pragma once
// The discrepancy question asked of a filter run (`stochnav diagnose --run`): do the filter's
// innovations on the data behave as its noise model says they should, and where not, which
// sensor, which time span and which noise effect explains it.
//
// For a consistent filter each innovation component, normalised by its predicted standard
// deviation, u_i(t) = z_i(t) / sqrt(S_ii(t)), is N(0, 1) and white. Per aid and component:
//   level     r = mean(u^2), about 1. Consecutive u are often correlated (a static-position aid
//             without measurement noise, say), so its spread uses the effective number of
//             terms nu = n (1 - rho^2) / (1 + rho^2) of an AR(1) sequence with lag-1
//             autocorrelation rho (the autocorrelation of u^2 is rho^(2k)): r ~ chi2(nu) / nu.
//   whiteness the Ljung-Box statistic Q = n (n + 2) sum_k rho_k^2 / (n - k) over L lags,
//             ~ chi2(L) for white u.
//   windows   r_w over consecutive windows of window_s seconds; each is compared with the
//             reference level r_ref (the median window level) by the F test
//             r_w / r_ref ~ F(nu_w, nu_ref), Bonferroni-corrected over windows. This part is
//             immune to a wrong R (or a wrong constant noise level): it asks whether the
//             model's noise should change over time.
// Findings, in the vocabulary of DESIGN.md:
//   nonstationary      windows well above the reference: the noise rose over that time span
//                      (scale = sqrt(level ratio) of the innovation standard deviation);
//   angle_random_walk  the level is too high throughout and u is white: white noise understated;
//   gauss_markov       too high or not white with a decaying autocorrelation: a correlated error
//                      is missing (tau_c estimated from rho_1 = exp(-dt / tau_c));
//   rate_random_walk   not white with an autocorrelation that hardly decays over L lags;
//   sinusoid           an autocorrelation that changes sign periodically (the period estimated
//                      from its zero crossings; aliased by the aid rate);
//   (effect null)      the level is too low throughout: the model (or R) overstates the noise.
// Sensor: from the aid's component meaning (static_position / position_fix / zupt: E, N, U
// position and velocity; pipe_length, rop: along-hole). Under static or near-static aiding the
// horizontal components carry the tilt error (gyro, through g x phi) and the horizontal
// accelerometers, the vertical component the vertical accelerometer.

#include <optional>
#include <string>
#include <vector>

namespace stochnav {

/// One row of a run's innovations.csv (experiment/run_files): the normalised innovation of
/// one aid update.
struct InnovationSample {
  double t_s = 0.0;           ///< time of the update (s)
  bool accepted = true;       ///< passed the NIS gate
  double nis = 0.0;           ///< z^T S^-1 z
  std::vector<double> z;      ///< innovation components (aid units)
  std::vector<double> sigma;  ///< sqrt(diag S), same units and length as z
};

/// The updates of one aid of the run, in time order.
struct AidInnovations {
  int aid_index = 0;
  std::string type;  ///< the aid plugin's type, e.g. "static_position"
  std::vector<InnovationSample> samples;
};

/// Reads RUN_DIR/innovations.csv, grouped by aid. Throws InputError "file:line: ..." for a
/// malformed file and when it has no updates.
std::vector<AidInnovations> read_innovations(const std::string& path);

struct InnovationAnalysisOptions {
  double window_s = 60.0;  ///< window of the level-over-time test (s), > 0
  double alpha = 0.01;     ///< false-alarm probability of each test family, in (0, 0.5)
  int max_lag = 10;        ///< lags of the whiteness test, >= 1
  /// Empty when valid; otherwise what is wrong and how to fix it.
  std::string validate() const;
};

struct ComponentStatistics {
  std::string name;                       ///< e.g. "position E (m)"
  std::string sensor_hint;                ///< e.g. "gyro tilt or horizontal accelerometer"
  double level = 0.0;                     ///< mean(u^2), 1 when consistent
  double level_lo = 0.0, level_hi = 0.0;  ///< the (1 - alpha) band of the level
  double rho1 = 0.0;                      ///< lag-1 autocorrelation of u
  std::vector<double> autocorrelation;    ///< rho_1 .. rho_L
  double ljung_box_p = 1.0;               ///< P(chi2(L) > Q)
  double effective_terms = 0.0;           ///< nu
};

struct LevelWindow {
  double t0_s = 0.0, t1_s = 0.0;  ///< window [t0, t1)
  std::vector<double> level;      ///< mean(u^2) per component
  std::vector<int> flag;          ///< per component: +1 above the reference, -1 below, 0 within
};

struct InnovationFinding {
  std::optional<std::string> effect;  ///< vocabulary name; nullopt: the noise is overstated
  std::string aid_type;
  std::vector<std::string> components;
  std::string sensor;
  std::optional<std::pair<double, double>> time_range_s;
  double scale = 1.0;              ///< innovation std ratio (level ratio^(1/2)) where it applies
  std::optional<double> tau_c_s;   ///< gauss_markov: estimated correlation time (s)
  std::optional<double> period_s;  ///< sinusoid: estimated (aliased) period (s)
  std::string evidence;            ///< one sentence with the numbers
};

struct AidAnalysis {
  int aid_index = 0;
  std::string type;
  std::size_t updates = 0;
  double update_interval_s = 0.0;  ///< median spacing of the updates
  std::vector<ComponentStatistics> components;
  std::vector<LevelWindow> windows;
  std::vector<double> reference_level;  ///< r_ref per component
};

struct InnovationAnalysis {
  std::vector<AidAnalysis> aids;
  std::vector<InnovationFinding> findings;
  /// No finding with an effect (an overstated noise alone is consistent but conservative).
  bool consistent = true;
};

/// Analyses the innovations of every aid. Aids with fewer than 20 updates are reported without
/// tests. Throws ConfigError for invalid options.
InnovationAnalysis analyse_innovations(const std::vector<AidInnovations>& aids,
                                       const InnovationAnalysisOptions& options);

}  // namespace stochnav

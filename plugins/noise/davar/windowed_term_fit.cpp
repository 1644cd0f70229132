#include "windowed_term_fit.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/stats/davar.hpp"
#include "stochnav/stats/edf.hpp"

namespace stochnav::davar_noise {
namespace {

/// Basis function of a term in Eq. 7: sigma^2(tau) = sum_k coefficient_k^2 basis_k(tau).
double basis(WindowTerm term, double tau_s) {
  switch (term) {
    case WindowTerm::kQuantization:
      return 3.0 / (tau_s * tau_s);
    case WindowTerm::kAngleRandomWalk:
      return 1.0 / tau_s;
    case WindowTerm::kBiasInstability:
      return 2.0 * std::numbers::ln2 / std::numbers::pi;
    case WindowTerm::kRateRandomWalk:
      return tau_s / 3.0;
  }
  return 0.0;
}

/// One window's Allan variances with their EDF and the basis matrix of all requested terms.
struct WindowData {
  Eigen::VectorXd avar;    // per tau
  Eigen::VectorXd edf;     // per tau
  Eigen::MatrixXd design;  // tau x term
};

/// Weighted non-negative least squares of avar ~ design * c, weights edf / (2 reference^2).
/// Returns c (squared coefficients), zero for dropped terms.
Eigen::VectorXd solve_non_negative(const WindowData& data, const Eigen::VectorXd& reference) {
  const Eigen::Index terms = data.design.cols();
  std::vector<bool> active(static_cast<std::size_t>(terms), true);
  Eigen::VectorXd solution = Eigen::VectorXd::Zero(terms);
  const Eigen::VectorXd weight = (data.edf.array() / (2.0 * reference.array().square())).matrix();
  for (Eigen::Index round = 0; round < terms; ++round) {
    std::vector<Eigen::Index> columns;
    for (Eigen::Index k = 0; k < terms; ++k) {
      if (active[static_cast<std::size_t>(k)]) columns.push_back(k);
    }
    if (columns.empty()) break;
    const auto n = static_cast<Eigen::Index>(columns.size());
    // Columns scaled to unit weighted norm: the basis spans many decades over the taus.
    Eigen::MatrixXd a(data.avar.size(), n);
    Eigen::VectorXd scale(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      a.col(j) = data.design.col(columns[static_cast<std::size_t>(j)]);
      scale(j) = std::sqrt((weight.array() * a.col(j).array().square()).sum());
      a.col(j) /= scale(j);
    }
    const Eigen::MatrixXd normal = a.transpose() * weight.asDiagonal() * a;
    const Eigen::VectorXd rhs = a.transpose() * weight.asDiagonal() * data.avar;
    const Eigen::VectorXd scaled = normal.ldlt().solve(rhs);
    solution.setZero();
    Eigen::Index most_negative = -1;
    double lowest = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double value = scaled(j) / scale(j);
      solution(columns[static_cast<std::size_t>(j)]) = value;
      if (value < lowest) {
        lowest = value;
        most_negative = columns[static_cast<std::size_t>(j)];
      }
    }
    if (most_negative < 0) return solution;
    active[static_cast<std::size_t>(most_negative)] = false;
  }
  return solution.cwiseMax(0.0);
}

/// Index of the angle random walk among `terms`; ConfigError when it is not one of them.
Eigen::Index angle_random_walk_column(const std::vector<WindowTerm>& terms) {
  const auto arw = std::find(terms.begin(), terms.end(), WindowTerm::kAngleRandomWalk);
  if (arw == terms.end()) {
    throw ConfigError("fit_terms_per_window: the terms must include the angle random walk");
  }
  return static_cast<Eigen::Index>(arw - terms.begin());
}

}  // namespace

DavarResult window_deviations(std::span<const double> rate_samples, double rate_hz,
                              double start_time_s, const WindowFitOptions& options) {
  if (!(rate_hz > 0.0)) throw ConfigError("fit_terms_per_window: rate_hz must be > 0");
  if (options.window < 16 || options.step < 1) {
    throw ConfigError("fit_terms_per_window: window must be >= 16 samples and step >= 1 (got " +
                      std::to_string(options.window) + ", " + std::to_string(options.step) + ")");
  }
  angle_random_walk_column(options.terms);
  if (rate_samples.size() < options.window) {
    throw InputError("fit_terms_per_window: the record (" + std::to_string(rate_samples.size()) +
                     " samples) is shorter than one window (" + std::to_string(options.window) +
                     " samples); use a shorter window or a longer record");
  }
  Record record;
  record.values.assign(rate_samples.begin(), rate_samples.end());
  record.rate_hz = rate_hz;
  record.start_time_s = start_time_s;
  const DavarOptions davar_options{
      .window = options.window, .step = options.step, .causal = options.causal, .m_values = {}};
  DavarResult davar = dynamic_allan_deviation(record, davar_options);
  if (davar.tau_s.size() < options.terms.size() + 1) {
    throw InputError("fit_terms_per_window: a window of " + std::to_string(options.window) +
                     " samples has " + std::to_string(davar.tau_s.size()) +
                     " octave taus, too few for " + std::to_string(options.terms.size()) +
                     " terms; use a longer window or fewer terms");
  }
  return davar;
}

WindowFitSeries fit_terms_per_window(std::span<const double> rate_samples, double rate_hz,
                                     double start_time_s, const WindowFitOptions& options) {
  return fit_window_deviations(window_deviations(rate_samples, rate_hz, start_time_s, options),
                               options);
}

WindowFitSeries fit_window_deviations(const DavarResult& davar, const WindowFitOptions& options) {
  const auto taus = static_cast<Eigen::Index>(davar.tau_s.size());
  const auto terms = static_cast<Eigen::Index>(options.terms.size());
  const Eigen::Index arw_column = angle_random_walk_column(options.terms);
  const auto b_term =
      std::find(options.terms.begin(), options.terms.end(), WindowTerm::kBiasInstability);
  const Eigen::Index b_column = static_cast<Eigen::Index>(b_term - options.terms.begin());
  const bool with_b = b_term != options.terms.end();

  Eigen::MatrixXd design(taus, terms);
  Eigen::VectorXd edf(taus);
  for (Eigen::Index i = 0; i < taus; ++i) {
    for (Eigen::Index k = 0; k < terms; ++k) {
      design(i, k) = basis(options.terms[static_cast<std::size_t>(k)], davar.tau_s[i]);
    }
    edf(i) = greenhall_edf({.alpha = 0,
                            .d = 2,
                            .m = davar.m[static_cast<std::size_t>(i)],
                            .phase_count = options.window + 1,
                            .overlapping = true});
  }

  WindowFitSeries series;
  series.time_s = davar.time_s;
  series.angle_random_walk.reserve(davar.adev.size());
  series.bias_instability.reserve(davar.adev.size());
  for (const auto& row : davar.adev) {
    // Points with a zero deviation (a constant stretch) carry no information on the noise.
    std::vector<Eigen::Index> usable;
    for (Eigen::Index i = 0; i < taus; ++i) {
      if (row[static_cast<std::size_t>(i)] > 0.0) usable.push_back(i);
    }
    WindowData data{Eigen::VectorXd(static_cast<Eigen::Index>(usable.size())),
                    Eigen::VectorXd(static_cast<Eigen::Index>(usable.size())),
                    Eigen::MatrixXd(static_cast<Eigen::Index>(usable.size()), terms)};
    for (Eigen::Index j = 0; j < data.avar.size(); ++j) {
      const Eigen::Index i = usable[static_cast<std::size_t>(j)];
      const double adev = row[static_cast<std::size_t>(i)];
      data.avar(j) = adev * adev;
      data.edf(j) = edf(i);
      data.design.row(j) = design.row(i);
    }
    if (data.avar.size() < terms + 1) {
      series.angle_random_walk.push_back(0.0);
      series.bias_instability.push_back(0.0);
      continue;
    }
    const Eigen::VectorXd pilot = solve_non_negative(data, data.avar);
    Eigen::VectorXd reference = data.design * pilot;
    // Where the pilot model vanishes, keep the measured value as the scale of the point.
    for (Eigen::Index j = 0; j < reference.size(); ++j) {
      if (!(reference(j) > 0.0)) reference(j) = data.avar(j);
    }
    const Eigen::VectorXd squared = solve_non_negative(data, reference);
    series.angle_random_walk.push_back(std::sqrt(squared(arw_column)));
    series.bias_instability.push_back(with_b ? std::sqrt(squared(b_column)) : 0.0);
  }
  return series;
}

}  // namespace stochnav::davar_noise

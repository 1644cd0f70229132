// Starting values of the GMWM fit: a grid over the Gauss-Markov correlation times with the
// variances solved exactly at each grid point (gmwm_fit.hpp, "Starting values").

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "gmwm_problem.hpp"
#include "stochnav/fit/implied_wavelet_variance.hpp"

namespace stochnav::gmwm_detail {
namespace {

/// Grid points of the correlation-time search kept at most (the combinations of repeated
/// Gauss-Markov terms grow as points^terms): per-octave density is halved until under it.
constexpr std::size_t kMaxGridCombinations = 3000;

struct Candidate {
  double objective = 0.0;
  std::vector<double> tau_c;     ///< per free Gauss-Markov term
  std::vector<double> variance;  ///< per linear coefficient solved (see LinearSolve)
};

/// min ||y - A v||^2 subject to v >= 0, exactly: the optimum is the unconstrained least-squares
/// solution on its own support, so every support whose solution is positive is tried (the
/// problems here have at most a handful of columns). Columns of zero norm get v = 0.
double non_negative_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& y,
                                  Eigen::VectorXd& v) {
  const auto columns = static_cast<int>(a.cols());
  Eigen::VectorXd norms = a.colwise().norm().transpose();
  double best = y.squaredNorm();
  v = Eigen::VectorXd::Zero(columns);
  if (columns == 0) return best;
  if (columns > 12) {  // not met by the term lists here; a clamped solve as a fallback
    v = a.colPivHouseholderQr().solve(y).cwiseMax(0.0);
    return (y - a * v).squaredNorm();
  }
  for (unsigned mask = 1; mask < (1u << columns); ++mask) {
    std::vector<int> support;
    for (int c = 0; c < columns; ++c) {
      if ((mask >> c & 1u) && norms[c] > 0.0) support.push_back(c);
    }
    if (support.size() != static_cast<std::size_t>(std::popcount(mask))) continue;
    Eigen::MatrixXd sub(a.rows(), static_cast<Eigen::Index>(support.size()));
    for (std::size_t i = 0; i < support.size(); ++i) {
      sub.col(static_cast<Eigen::Index>(i)) = a.col(support[i]) / norms[support[i]];
    }
    const Eigen::VectorXd scaled = sub.householderQr().solve(y);
    if ((scaled.array() <= 0.0).any()) continue;
    const double objective = (y - sub * scaled).squaredNorm();
    if (objective < best) {
      best = objective;
      v.setZero();
      for (std::size_t i = 0; i < support.size(); ++i) {
        v[support[i]] = scaled[static_cast<Eigen::Index>(i)] / norms[support[i]];
      }
    }
  }
  return best;
}

class StartSearch {
 public:
  explicit StartSearch(const GmwmProblem& problem) : problem_(problem) {
    for (std::size_t t = 0; t < problem.terms.size(); ++t) {
      const std::size_t k = problem.offset[t];
      if (!problem.fixed_log[k]) linear_terms_.push_back(t);
      if (problem.terms[t] == TermType::kGaussMarkov && !problem.fixed_log[k + 1] &&
          !problem.start_log[k + 1]) {
        free_gm_terms_.push_back(t);
      }
    }
  }

  std::vector<Candidate> search() const {
    const std::size_t k = free_gm_terms_.size();
    std::vector<double> grid = correlation_time_grid(k);
    std::vector<Candidate> candidates;
    std::vector<std::size_t> index(k);
    for (std::size_t i = 0; i < k; ++i) index[i] = i;
    if (k > grid.size()) return {evaluate({})};
    while (true) {
      std::vector<double> tau(k);
      for (std::size_t i = 0; i < k; ++i) tau[i] = grid[index[i]];
      candidates.push_back(evaluate(tau));
      // Next strictly increasing index combination.
      std::size_t i = k;
      while (i > 0 && index[i - 1] == grid.size() - k + (i - 1)) --i;
      if (i == 0) break;
      ++index[i - 1];
      for (std::size_t m = i; m < k; ++m) index[m] = index[m - 1] + 1;
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.objective < b.objective; });
    return candidates;
  }

  std::vector<double> to_log_parameters(const Candidate& candidate) const {
    const GmwmProblem& p = problem_;
    std::vector<double> log(p.parameter_count, 0.0);
    for (std::size_t t = 0; t < p.terms.size(); ++t) {
      const std::size_t k = p.offset[t];
      if (p.terms[t] == TermType::kGaussMarkov) log[k + 1] = tau_log(candidate, t);
    }
    for (std::size_t i = 0; i < linear_terms_.size(); ++i) {
      const std::size_t k = p.offset[linear_terms_[i]];
      // A coefficient the solve set to zero starts a millionth of the way up its range.
      const double floor = p.lower_log[k] + 0.5 * std::log(1e6);
      log[k] = candidate.variance[i] > 0.0 ? std::max(0.5 * std::log(candidate.variance[i]), floor)
                                           : floor;
    }
    for (std::size_t k = 0; k < p.parameter_count; ++k) {
      if (p.start_log[k]) log[k] = *p.start_log[k];
      if (p.fixed_log[k]) log[k] = *p.fixed_log[k];
      // Strictly inside the box: Ceres refuses a start on a bound.
      const double margin = 1e-6 * (p.upper_log[k] - p.lower_log[k]);
      if (!p.fixed_log[k])
        log[k] = std::clamp(log[k], p.lower_log[k] + margin, p.upper_log[k] - margin);
    }
    return log;
  }

  /// log2 distance between two candidates' correlation times (the largest over the terms).
  static double octaves_apart(const Candidate& a, const Candidate& b) {
    double d = 0.0;
    for (std::size_t i = 0; i < a.tau_c.size(); ++i) {
      d = std::max(d, std::abs(std::log2(a.tau_c[i] / b.tau_c[i])));
    }
    return d;
  }

 private:
  std::vector<double> correlation_time_grid(std::size_t terms) const {
    const double low = kGmwmMinCorrelationTimeSamples * problem_.tau0_s;
    const double high = problem_.scale_s.back();
    const double octaves = std::log2(high / low);
    for (double per_octave = 4.0;; per_octave /= 2.0) {
      const auto points = static_cast<std::size_t>(std::floor(octaves * per_octave)) + 1;
      double combinations = 1.0;
      for (std::size_t i = 0; i < terms; ++i) {
        combinations *=
            static_cast<double>(points - std::min(points, i)) / static_cast<double>(i + 1);
      }
      if (combinations <= kMaxGridCombinations || per_octave <= 0.5) {
        std::vector<double> grid(points);
        for (std::size_t i = 0; i < points; ++i) {
          grid[i] = low * std::exp2(static_cast<double>(i) / per_octave);
        }
        return grid;
      }
    }
  }

  double tau_log(const Candidate& candidate, std::size_t term) const {
    const std::size_t k = problem_.offset[term] + 1;
    if (problem_.fixed_log[k]) return *problem_.fixed_log[k];
    if (problem_.start_log[k]) return *problem_.start_log[k];
    const auto at = std::find(free_gm_terms_.begin(), free_gm_terms_.end(), term);
    return std::log(candidate.tau_c[static_cast<std::size_t>(at - free_gm_terms_.begin())]);
  }

  Candidate evaluate(const std::vector<double>& tau) const {
    const GmwmProblem& p = problem_;
    Candidate candidate;
    candidate.tau_c = tau;
    const auto rows = static_cast<Eigen::Index>(p.scale_s.size());
    Eigen::MatrixXd a(rows, static_cast<Eigen::Index>(linear_terms_.size()));
    Eigen::VectorXd y(rows);
    for (Eigen::Index j = 0; j < rows; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      double fixed_part = 0.0;
      Eigen::Index column = 0;
      for (std::size_t t = 0; t < p.terms.size(); ++t) {
        const std::size_t k = p.offset[t];
        double parameters[2] = {1.0, 0.0};
        if (p.terms[t] == TermType::kGaussMarkov) parameters[1] = std::exp(tau_log(candidate, t));
        const double unit_wv =
            term_wavelet_variance(p.terms[t], parameters, p.scale_s[jj], p.tau0_s, p.sampling);
        if (p.fixed_log[k]) {
          fixed_part += std::exp(2.0 * *p.fixed_log[k]) * unit_wv;
        } else {
          a(j, column++) = unit_wv * p.sqrt_weight[jj];
        }
      }
      y[j] = (p.wv[jj] - fixed_part) * p.sqrt_weight[jj];
    }
    Eigen::VectorXd v;
    candidate.objective = non_negative_least_squares(a, y, v);
    candidate.variance.assign(v.data(), v.data() + v.size());
    return candidate;
  }

  const GmwmProblem& problem_;
  std::vector<std::size_t> linear_terms_;   ///< terms whose coefficient is solved
  std::vector<std::size_t> free_gm_terms_;  ///< Gauss-Markov terms whose tau_c is searched
};

}  // namespace

std::vector<std::vector<double>> gmwm_starting_points(const GmwmProblem& problem,
                                                      std::size_t count) {
  const StartSearch search(problem);
  const std::vector<Candidate> ranked = search.search();
  // The best candidates at least an octave apart from those kept: distinct basins.
  std::vector<const Candidate*> kept;
  for (const auto& candidate : ranked) {
    if (kept.size() >= count) break;
    const bool distinct = std::all_of(kept.begin(), kept.end(), [&](const Candidate* other) {
      return StartSearch::octaves_apart(candidate, *other) >= 1.0;
    });
    if (distinct) kept.push_back(&candidate);
  }
  std::vector<std::vector<double>> starts;
  for (const Candidate* candidate : kept) starts.push_back(search.to_log_parameters(*candidate));
  return starts;
}

}  // namespace stochnav::gmwm_detail

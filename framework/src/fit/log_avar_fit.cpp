#include "log_avar_fit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/trigamma.hpp>
#include <cmath>
#include <limits>
#include <memory>

#include "stochnav/model/allan_variance.hpp"
#include "stochnav/model/closed_forms.hpp"

namespace stochnav::fit_detail {
namespace {

// Allan variance of one term from the logs of its parameters.
template <typename T>
T term_avar(TermType type, const T* log_p, double tau) {
  using std::exp;
  switch (type) {
    case TermType::kQuantization:
      return closed_form::quantization_avar(exp(log_p[0]), tau);
    case TermType::kAngleRandomWalk:
      return closed_form::angle_random_walk_avar(exp(log_p[0]), tau);
    case TermType::kBiasInstability:
      return closed_form::bias_instability_avar(exp(log_p[0]));
    case TermType::kRateRandomWalk:
      return closed_form::rate_random_walk_avar(exp(log_p[0]), tau);
    case TermType::kRateRamp:
      return closed_form::rate_ramp_avar(exp(log_p[0]), tau);
    case TermType::kGaussMarkov:
      return closed_form::gauss_markov_avar(exp(log_p[0]), exp(log_p[1]), tau);
    case TermType::kSinusoid:
      return closed_form::sinusoid_avar(exp(log_p[0]), exp(log_p[1]), tau);
    case TermType::kNonstationary:
    case TermType::kBiasStep:
    case TermType::kAuxSensitivity:
      break;
  }
  return T(0.0);
}

// A term with at least one free parameter: its fixed parameters' values and which are free.
struct TermLayout {
  TermType type = TermType::kAngleRandomWalk;
  std::array<double, 2> log_values{};  // fixed entries hold their values
  std::array<bool, 2> free{};
};

// r = (log model(tau) - target) / s for one point; one parameter block per term with a free
// parameter, holding its free parameters only (fixed ones are constants of the cost).
struct LogAvarResidual {
  const std::vector<TermLayout>* layouts;
  double tau;
  double target;
  double inv_sigma;
  double background;  // AVAR of the held terms and of the terms with every parameter fixed

  template <typename T>
  bool operator()(T const* const* parameters, T* residual) const {
    T sum(background);
    for (std::size_t j = 0; j < layouts->size(); ++j) {
      const TermLayout& layout = (*layouts)[j];
      std::array<T, 2> log_p{T(layout.log_values[0]), T(layout.log_values[1])};
      std::size_t next = 0;
      for (std::size_t k = 0; k < 2; ++k) {
        if (layout.free[k]) log_p[k] = parameters[j][next++];
      }
      sum += term_avar(layout.type, log_p.data(), tau);
    }
    if (!(sum > T(0.0))) return false;
    using std::log;
    residual[0] = (log(sum) - target) * inv_sigma;
    return true;
  }
};

// Everything a Ceres problem points into: kept alive while the problem is used.
struct BuiltProblem {
  std::vector<TermLayout> layouts;
  std::vector<std::size_t> term_of_block;               // index into the solution's terms
  std::vector<std::vector<std::size_t>> free_of_block;  // parameter indexes k of each block
  std::vector<std::vector<double>> blocks;
  std::unique_ptr<ceres::LossFunction> loss;
  std::unique_ptr<ceres::Problem> problem;
};

std::unique_ptr<ceres::LossFunction> make_loss(RobustLoss loss, double scale) {
  switch (loss) {
    case RobustLoss::kHuber:
      return std::make_unique<ceres::HuberLoss>(scale);
    case RobustLoss::kCauchy:
      return std::make_unique<ceres::CauchyLoss>(scale);
    case RobustLoss::kNone:
      break;
  }
  return nullptr;
}

constexpr double kCoefficientDecadesBelow = 14.0;  // e-folds below the read-off
constexpr double kCoefficientDecadesAbove = 3.0;

}  // namespace

std::size_t parameter_count(TermType type) {
  switch (type) {
    case TermType::kGaussMarkov:
    case TermType::kSinusoid:
      return 2;
    case TermType::kNonstationary:
    case TermType::kBiasStep:
    case TermType::kAuxSensitivity:
      return 0;
    default:
      return 1;
  }
}

LogAvarFit::LogAvarFit(const FitData& data, const FitOptions& options,
                       std::span<const double> edf, Eigen::MatrixXd correlation)
    : tau_(data.tau_s),
      avar_(data.avar),
      correlation_(std::move(correlation)),
      options_(options),
      readoffs_(slope_readoffs(data)) {
  for (std::size_t i = 0; i < tau_.size(); ++i) {
    const double half_nu = 0.5 * edf[i];
    const double bias = boost::math::digamma(half_nu) - std::log(half_nu);
    target_.push_back(std::log(avar_[i]) - bias);
    inv_sigma_.push_back(1.0 / std::sqrt(boost::math::trigamma(half_nu)));
    double background = 0.0;
    for (const NoiseTerm& term : options.fixed_terms) background += allan_variance(term, tau_[i]);
    background_.push_back(background);
  }
  const auto [avar_min, avar_max] = std::minmax_element(avar_.begin(), avar_.end());
  log_root_avar_min_ = 0.5 * std::log(*avar_min);
  log_root_avar_max_ = 0.5 * std::log(*avar_max);
  const auto [tau_min, tau_max] = std::minmax_element(tau_.begin(), tau_.end());
  tau_min_ = *tau_min;
  tau_max_ = *tau_max;
}

double LogAvarFit::lower_bound(TermType type, std::size_t k) const {
  switch (type) {
    case TermType::kQuantization:
      return std::log(readoffs_.quantization.value) - kCoefficientDecadesBelow;
    case TermType::kAngleRandomWalk:
      return std::log(readoffs_.angle_random_walk.value) - kCoefficientDecadesBelow;
    case TermType::kBiasInstability:
      return std::log(readoffs_.bias_instability.value) - kCoefficientDecadesBelow;
    case TermType::kRateRandomWalk:
      return std::log(readoffs_.rate_random_walk.value) - kCoefficientDecadesBelow;
    case TermType::kRateRamp:
      return std::log(readoffs_.rate_ramp.value) - kCoefficientDecadesBelow;
    case TermType::kGaussMarkov:
      // A correlation time below the shortest tau (the sampling interval) is white noise
      // aliased by the sampling: the data cannot tell it from angle random walk.
      return k == 0 ? log_root_avar_min_ - kCoefficientDecadesBelow : std::log(tau_min_);
    case TermType::kSinusoid:
      return k == 0 ? log_root_avar_min_ - kCoefficientDecadesBelow : std::log(0.01 / tau_max_);
    case TermType::kNonstationary:
    case TermType::kBiasStep:
    case TermType::kAuxSensitivity:
      break;
  }
  return -std::numeric_limits<double>::infinity();
}

double LogAvarFit::upper_bound(TermType type, std::size_t k) const {
  switch (type) {
    case TermType::kQuantization:
      return std::log(readoffs_.quantization.value) + kCoefficientDecadesAbove;
    case TermType::kAngleRandomWalk:
      return std::log(readoffs_.angle_random_walk.value) + kCoefficientDecadesAbove;
    case TermType::kBiasInstability:
      return std::log(readoffs_.bias_instability.value) + kCoefficientDecadesAbove;
    case TermType::kRateRandomWalk:
      return std::log(readoffs_.rate_random_walk.value) + kCoefficientDecadesAbove;
    case TermType::kRateRamp:
      return std::log(readoffs_.rate_ramp.value) + kCoefficientDecadesAbove;
    case TermType::kGaussMarkov:
      // A Gauss-Markov term far outside the tau range mimics a random walk or white noise with
      // a large sigma, so sigma gets more room above than the other coefficients.
      return k == 0 ? log_root_avar_max_ + 10.0 : std::log(tau_max_ * 100.0);
    case TermType::kSinusoid:
      return k == 0 ? log_root_avar_max_ + kCoefficientDecadesAbove : std::log(1.0 / tau_min_);
    case TermType::kNonstationary:
    case TermType::kBiasStep:
    case TermType::kAuxSensitivity:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

const ParameterControl* LogAvarFit::control(const TermParameters& term, std::size_t k) const {
  if (term.slot == kNoSlot) return nullptr;
  for (const ParameterControl& c : options_.controls) {
    if (c.term == term.slot && c.parameter == k) return &c;
  }
  return nullptr;
}

double LogAvarFit::lower_bound(const TermParameters& term, std::size_t k) const {
  const ParameterControl* c = control(term, k);
  return c != nullptr && c->lower ? std::log(*c->lower) : lower_bound(term.type, k);
}

double LogAvarFit::upper_bound(const TermParameters& term, std::size_t k) const {
  const ParameterControl* c = control(term, k);
  return c != nullptr && c->upper ? std::log(*c->upper) : upper_bound(term.type, k);
}

bool LogAvarFit::is_fixed(const TermParameters& term, std::size_t k) const {
  const ParameterControl* c = control(term, k);
  return c != nullptr && c->fixed.has_value();
}

namespace {

// Whether a log value sits on (within 1e-6 of the range of) the lower or upper edge.
std::pair<bool, bool> on_edges(double value, double lower, double upper) {
  const double margin = 1e-6 * (upper - lower);
  return {value <= lower + margin, value >= upper - margin};
}

}  // namespace

bool LogAvarFit::at_bound(const TermParameters& term, std::size_t k) const {
  if (is_fixed(term, k)) return false;
  const ParameterControl* c = control(term, k);
  const auto [on_lower, on_upper] =
      on_edges(term.log_values[k], lower_bound(term, k), upper_bound(term, k));
  return (on_lower && !(c != nullptr && c->lower)) || (on_upper && !(c != nullptr && c->upper));
}

bool LogAvarFit::on_given_bound(const TermParameters& term, std::size_t k) const {
  const ParameterControl* c = control(term, k);
  if (c == nullptr || c->fixed) return false;
  const auto [on_lower, on_upper] =
      on_edges(term.log_values[k], lower_bound(term, k), upper_bound(term, k));
  return (on_lower && c->lower) || (on_upper && c->upper);
}

std::vector<std::vector<double>> LogAvarFit::starts(TermType type, std::size_t slot) const {
  std::vector<std::vector<double>> searched = searched_starts(type);
  const TermParameters steered_term{type, {}, slot};
  bool steered = false;
  for (std::size_t k = 0; k < parameter_count(type); ++k) {
    const ParameterControl* c = control(steered_term, k);
    const std::optional<double> given = c == nullptr ? std::nullopt
                                        : c->fixed   ? c->fixed
                                                     : c->start;
    if (!given) continue;
    steered = true;
    for (auto& start : searched) start[k] = std::log(*given);
  }
  if (!steered) return searched;
  // Starts that differed only in a given value are now the same start.
  std::sort(searched.begin(), searched.end());
  searched.erase(std::unique(searched.begin(), searched.end()), searched.end());
  return searched;
}

std::vector<std::vector<double>> LogAvarFit::searched_starts(TermType type) const {
  std::vector<std::vector<double>> result;
  const auto scaled = [&](double readoff) {
    for (double factor : {0.7, 0.2, 0.03}) result.push_back({std::log(factor * readoff)});
  };
  switch (type) {
    case TermType::kQuantization:
      scaled(readoffs_.quantization.value);
      break;
    case TermType::kAngleRandomWalk:
      scaled(readoffs_.angle_random_walk.value);
      break;
    case TermType::kBiasInstability:
      scaled(readoffs_.bias_instability.value);
      break;
    case TermType::kRateRandomWalk:
      scaled(readoffs_.rate_random_walk.value);
      break;
    case TermType::kRateRamp:
      scaled(readoffs_.rate_ramp.value);
      break;
    case TermType::kGaussMarkov:
      // Peak of the Gauss-Markov AVAR: 0.381 sigma^2 at tau = 1.89 tau_c.
      for (std::size_t i = 0; i < tau_.size(); ++i) {
        result.push_back({std::log(0.5 * std::sqrt(avar_[i] / 0.381)), std::log(tau_[i] / 1.89)});
      }
      break;
    case TermType::kSinusoid:
      // The frequencies whose nulls (tau = k / f) and peaks best match the curve first, then
      // the peak of the sinusoid AVAR, 0.525 A^2 at tau = 0.371 / f, at every measured tau.
      result = sinusoid_frequency_scan();
      for (std::size_t i = 0; i < tau_.size(); ++i) {
        result.push_back({std::log(0.5 * std::sqrt(avar_[i] / 0.525)), std::log(0.371 / tau_[i])});
      }
      break;
    case TermType::kNonstationary:
    case TermType::kBiasStep:
    case TermType::kAuxSensitivity:
      break;
  }
  return result;
}

std::vector<std::vector<double>> LogAvarFit::sinusoid_frequency_scan() const {
  // The sinusoid's AVAR, A^2 sin^4(pi f tau) / (pi f tau)^2, dips towards zero at tau = k / f:
  // an octave tau set samples it too sparsely for a start at its peak to find the right one of
  // the many local optima in f (a clean 0.05 Hz sinusoid converged to 0.0715 Hz). On a grid of
  // frequencies over the fitted range (16 per octave), the best amplitude is closed-form in the
  // log domain (the weighted mean of target_i - log shape_i(f)), and so is the misfit; the three
  // best local minima of the misfit over the grid are the starts. Points where the shape
  // vanishes (log -> -inf) make a frequency's misfit infinite, never a start.
  const double log_f_low = lower_bound(TermType::kSinusoid, 1);
  const double log_f_high = upper_bound(TermType::kSinusoid, 1);
  constexpr double kStepsPerOctave = 16.0;
  const double step = std::log(2.0) / kStepsPerOctave;
  struct GridPoint {
    double log_f;
    double log_amplitude;
    double misfit;
  };
  std::vector<GridPoint> grid;
  for (double log_f = log_f_low + 0.5 * step; log_f < log_f_high; log_f += step) {
    const double f = std::exp(log_f);
    double weight_sum = 0.0;
    double weighted = 0.0;
    std::vector<double> log_shape(tau_.size());
    bool finite = true;
    for (std::size_t i = 0; i < tau_.size(); ++i) {
      log_shape[i] = std::log(closed_form::sinusoid_avar(1.0, f, tau_[i]));
      if (!std::isfinite(log_shape[i])) finite = false;
      const double w = inv_sigma_[i] * inv_sigma_[i];
      weight_sum += w;
      weighted += w * (target_[i] - log_shape[i]);
    }
    if (!finite || !(weight_sum > 0.0)) continue;
    const double log_amplitude_squared = weighted / weight_sum;
    double misfit = 0.0;
    for (std::size_t i = 0; i < tau_.size(); ++i) {
      const double r = (log_amplitude_squared + log_shape[i] - target_[i]) * inv_sigma_[i];
      misfit += r * r;
    }
    grid.push_back({log_f, 0.5 * log_amplitude_squared, misfit});
  }
  std::vector<GridPoint> minima;
  for (std::size_t j = 0; j < grid.size(); ++j) {
    const bool below_left = j == 0 || grid[j].misfit <= grid[j - 1].misfit;
    const bool below_right = j + 1 == grid.size() || grid[j].misfit <= grid[j + 1].misfit;
    if (below_left && below_right && std::isfinite(grid[j].misfit)) minima.push_back(grid[j]);
  }
  std::sort(minima.begin(), minima.end(),
            [](const GridPoint& a, const GridPoint& b) { return a.misfit < b.misfit; });
  constexpr std::size_t kScanStarts = 3;
  std::vector<std::vector<double>> starts;
  for (std::size_t j = 0; j < minima.size() && j < kScanStarts; ++j) {
    starts.push_back({minima[j].log_amplitude, minima[j].log_f});
  }
  return starts;
}

namespace {

// Which parameters of each term are fitted (the others fixed at their log_values).
using FreeMask = std::vector<std::array<bool, 2>>;

BuiltProblem build_problem(const std::vector<TermParameters>& terms, const FreeMask& free,
                           const std::vector<double>& tau, const std::vector<double>& target,
                           const std::vector<double>& inv_sigma,
                           const std::vector<double>& background, const FitOptions& options) {
  BuiltProblem built;
  std::vector<TermLayout> held;  // terms with every parameter fixed: part of the background
  for (std::size_t j = 0; j < terms.size(); ++j) {
    TermLayout layout{terms[j].type, {}, {}};
    std::vector<double> block;
    std::vector<std::size_t> free_k;
    for (std::size_t k = 0; k < terms[j].log_values.size(); ++k) {
      layout.log_values[k] = terms[j].log_values[k];
      layout.free[k] = free[j][k];
      if (!free[j][k]) continue;
      block.push_back(terms[j].log_values[k]);
      free_k.push_back(k);
    }
    if (block.empty()) {
      held.push_back(layout);
      continue;
    }
    built.layouts.push_back(layout);
    built.term_of_block.push_back(j);
    built.free_of_block.push_back(std::move(free_k));
    built.blocks.push_back(std::move(block));
  }
  built.loss = make_loss(options.loss, options.loss_scale);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  built.problem = std::make_unique<ceres::Problem>(problem_options);
  std::vector<double*> pointers;
  for (auto& block : built.blocks) pointers.push_back(block.data());
  for (std::size_t i = 0; i < tau.size(); ++i) {
    double held_avar = background[i];
    for (const TermLayout& layout : held) {
      held_avar += term_avar(layout.type, layout.log_values.data(), tau[i]);
    }
    auto* cost = new ceres::DynamicAutoDiffCostFunction<LogAvarResidual, 4>(
        new LogAvarResidual{&built.layouts, tau[i], target[i], inv_sigma[i], held_avar});
    for (const auto& block : built.blocks) cost->AddParameterBlock(static_cast<int>(block.size()));
    cost->SetNumResiduals(1);
    built.problem->AddResidualBlock(cost, built.loss.get(), pointers);
  }
  return built;
}

}  // namespace

Solution LogAvarFit::solve(std::vector<TermParameters> start) const {
  Solution solution;
  FreeMask free(start.size(), {false, false});
  for (std::size_t j = 0; j < start.size(); ++j) {
    TermParameters& term = start[j];
    for (std::size_t k = 0; k < term.log_values.size(); ++k) {
      if (const ParameterControl* c = control(term, k); c != nullptr && c->fixed) {
        term.log_values[k] = std::log(*c->fixed);
        continue;
      }
      free[j][k] = true;
      term.log_values[k] =
          std::clamp(term.log_values[k], lower_bound(term, k), upper_bound(term, k));
      ++solution.parameter_count;
    }
  }
  BuiltProblem built = build_problem(start, free, tau_, target_, inv_sigma_, background_, options_);
  for (std::size_t b = 0; b < built.blocks.size(); ++b) {
    const TermParameters& term = start[built.term_of_block[b]];
    for (std::size_t i = 0; i < built.free_of_block[b].size(); ++i) {
      const std::size_t k = built.free_of_block[b][i];
      built.problem->SetParameterLowerBound(built.blocks[b].data(), static_cast<int>(i),
                                            lower_bound(term, k));
      built.problem->SetParameterUpperBound(built.blocks[b].data(), static_cast<int>(i),
                                            upper_bound(term, k));
    }
  }
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options_.max_iterations;
  solver_options.function_tolerance = 1e-12;
  solver_options.gradient_tolerance = 1e-12;
  solver_options.parameter_tolerance = 1e-10;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, built.problem.get(), &summary);

  solution.usable = summary.IsSolutionUsable();
  solution.converged = summary.termination_type == ceres::CONVERGENCE;
  solution.iterations = static_cast<int>(summary.iterations.size()) - 1;
  solution.cost = summary.final_cost;
  solution.terms = std::move(start);
  for (std::size_t b = 0; b < built.blocks.size(); ++b) {
    TermParameters& term = solution.terms[built.term_of_block[b]];
    for (std::size_t i = 0; i < built.free_of_block[b].size(); ++i) {
      term.log_values[built.free_of_block[b][i]] = built.blocks[b][i];
    }
  }
  ceres::Problem::EvaluateOptions evaluate_options;
  evaluate_options.apply_loss_function = false;
  std::vector<double> residuals;
  double raw_cost = 0.0;
  if (built.problem->Evaluate(evaluate_options, &raw_cost, &residuals, nullptr, nullptr)) {
    solution.chi_square = 2.0 * raw_cost;
  } else {
    solution.usable = false;
  }
  if (!std::isfinite(solution.cost)) solution.usable = false;
  return solution;
}

Eigen::MatrixXd LogAvarFit::covariance(const Solution& solution) const {
  Eigen::Index n = 0;
  FreeMask free(solution.terms.size(), {false, false});
  std::vector<Eigen::Index> offset_of_term;
  for (std::size_t j = 0; j < solution.terms.size(); ++j) {
    offset_of_term.push_back(n);
    for (std::size_t k = 0; k < solution.terms[j].log_values.size(); ++k, ++n) {
      free[j][k] = !is_fixed(solution.terms[j], k);
    }
  }
  Eigen::MatrixXd nan_matrix =
      Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return nan_matrix;
  const auto m = static_cast<Eigen::Index>(solution.parameter_count);
  BuiltProblem built =
      build_problem(solution.terms, free, tau_, target_, inv_sigma_, background_, options_);
  // Free parameter i of the blocks (Ceres' order) is entry index_of_free[i] of the result.
  std::vector<Eigen::Index> index_of_free;
  for (std::size_t b = 0; b < built.blocks.size(); ++b) {
    for (std::size_t k : built.free_of_block[b]) {
      index_of_free.push_back(offset_of_term[built.term_of_block[b]] +
                              static_cast<Eigen::Index>(k));
    }
  }
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(n, n);  // fixed parameters: 0
  if (m > 0) {
    ceres::Covariance::Options covariance_options;
    covariance_options.algorithm_type = ceres::DENSE_SVD;
    covariance_options.null_space_rank = -1;
    covariance_options.min_reciprocal_condition_number = 1e-14;
    covariance_options.num_threads = 1;
    ceres::Covariance covariance(covariance_options);
    std::vector<const double*> pointers;
    for (const auto& block : built.blocks) pointers.push_back(block.data());
    if (!covariance.Compute(pointers, built.problem.get())) return nan_matrix;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> matrix(m, m);
    if (!covariance.GetCovarianceMatrix(pointers, matrix.data())) return nan_matrix;
    Eigen::MatrixXd free_covariance = matrix;
    if (correlation_.rows() == static_cast<Eigen::Index>(tau_.size())) {
      // Sandwich for correlated residuals: C J^T R J C, J with the same loss corrections.
      ceres::Problem::EvaluateOptions evaluate_options;
      evaluate_options.apply_loss_function = true;
      double cost = 0.0;
      ceres::CRSMatrix crs;
      if (!built.problem->Evaluate(evaluate_options, &cost, nullptr, nullptr, &crs)) {
        return nan_matrix;
      }
      Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
      for (int row = 0; row < crs.num_rows; ++row) {
        for (int k = crs.rows[static_cast<std::size_t>(row)];
             k < crs.rows[static_cast<std::size_t>(row) + 1]; ++k) {
          jacobian(row, crs.cols[static_cast<std::size_t>(k)]) =
              crs.values[static_cast<std::size_t>(k)];
        }
      }
      const Eigen::MatrixXd bread = free_covariance;
      free_covariance = bread * (jacobian.transpose() * correlation_ * jacobian) * bread;
    }
    for (Eigen::Index i = 0; i < m; ++i) {
      for (Eigen::Index k = 0; k < m; ++k) {
        result(index_of_free[static_cast<std::size_t>(i)],
               index_of_free[static_cast<std::size_t>(k)]) = free_covariance(i, k);
      }
    }
  }
  // Parameters pinned at a search bound have no meaningful variance.
  Eigen::Index offset = 0;
  for (const auto& term : solution.terms) {
    for (std::size_t k = 0; k < term.log_values.size(); ++k, ++offset) {
      if (at_bound(term, k)) {
        result.row(offset).setConstant(std::numeric_limits<double>::quiet_NaN());
        result.col(offset).setConstant(std::numeric_limits<double>::quiet_NaN());
      }
    }
  }
  return result;
}

}  // namespace stochnav::fit_detail

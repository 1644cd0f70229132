#include "stochnav/diagnose/deterministic_effects.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/effective_model.hpp"

namespace stochnav {
namespace {

constexpr std::size_t kMinBlockSamples = 16;
constexpr std::size_t kMinBlocks = 16;

// Generalized phase covariance G(h) of the stochastic terms (h in s); see the header.
double phase_covariance(const NoiseModel& model, double h) {
  h = std::abs(h);
  double g = 0.0;
  for (const auto& term : model.terms) {
    if (const auto* q = std::get_if<QuantizationTerm>(&term)) {
      if (h == 0.0) g += q->q * q->q;
    } else if (const auto* arw = std::get_if<AngleRandomWalkTerm>(&term)) {
      g -= 0.5 * arw->n * arw->n * h;
    } else if (const auto* bi = std::get_if<BiasInstabilityTerm>(&term)) {
      if (h > 0.0) g += bi->b * bi->b * h * h * std::log(h) / (2.0 * std::numbers::pi);
    } else if (const auto* rrw = std::get_if<RateRandomWalkTerm>(&term)) {
      g += rrw->k * rrw->k * h * h * h / 12.0;
    } else if (const auto* gm = std::get_if<GaussMarkovTerm>(&term)) {
      if (gm->sigma > 0.0) {
        g -= gm->sigma * gm->sigma * gm->tau_c * gm->tau_c * (h / gm->tau_c + std::exp(-h / gm->tau_c));
      }
    } else if (const auto* sine = std::get_if<SinusoidTerm>(&term)) {
      const double w = 2.0 * std::numbers::pi * sine->frequency_hz;
      g += sine->amplitude * sine->amplitude * std::cos(w * h) / (2.0 * w * w);
    }
  }
  return g;
}

// Covariance of the first differences of block means (length n, block length T).
template <typename PhaseCovariance>
Eigen::MatrixXd difference_covariance(std::size_t n, double block_s, PhaseCovariance&& g) {
  constexpr std::array<double, 3> a{1.0, -2.0, 1.0};
  std::vector<double> by_lag(n);
  for (std::size_t lag = 0; lag < n; ++lag) {
    double c = 0.0;
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        c += a[p] * a[q] * g((static_cast<double>(lag) + p - q) * block_s);
      }
    }
    by_lag[lag] = c / (block_s * block_s);
  }
  Eigen::MatrixXd s(n, n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) s(i, j) = by_lag[i > j ? i - j : j - i];
  }
  return s;
}

// A GLS fit of d = X b + e, e ~ s^2 (S0 + k S_K), with s^2 and k profiled out.
struct GlsFit {
  double minus_two_log_l = std::numeric_limits<double>::infinity();
  Eigen::VectorXd beta;
  Eigen::MatrixXd beta_covariance;
  double k_share = 0.0;
  double scale2 = 1.0;  ///< the profiled s^2
};

class DifferenceModel {
 public:
  DifferenceModel(Eigen::VectorXd d, const Eigen::MatrixXd& s0, const Eigen::MatrixXd& s_k)
      : d_(std::move(d)) {
    // k on a log grid relative to the white level of S0 (plus k = 0).
    scale_ = s0.diagonal().mean() / std::max(s_k.diagonal().mean(), 1e-300);
    const double scale = scale_;
    std::vector<double> shares{0.0};
    for (double e = -4.0; e <= 3.01; e += 0.25) shares.push_back(std::pow(10.0, e));
    for (double share : shares) {
      Eigen::MatrixXd s = s0 + share * scale * s_k;
      Eigen::LLT<Eigen::MatrixXd> llt(s);
      if (llt.info() != Eigen::Success) continue;
      double log_det = 0.0;
      for (Eigen::Index i = 0; i < s.rows(); ++i) log_det += 2.0 * std::log(llt.matrixL()(i, i));
      factors_.push_back({share, std::move(llt), log_det});
    }
    if (factors_.empty()) throw ConfigError("diagnose: the model's block covariance is singular");
  }

  // with_random_walk false: k = 0 (S0 alone).
  GlsFit fit(const Eigen::MatrixXd& x, bool with_random_walk) const {
    GlsFit best;
    const auto n = static_cast<double>(d_.size());
    for (const auto& factor : factors_) {
      if (!with_random_walk && factor.share != 0.0) continue;
      const Eigen::VectorXd wd = factor.llt.matrixL().solve(d_);
      Eigen::VectorXd residual = wd;
      Eigen::VectorXd beta;
      Eigen::MatrixXd xtx_inverse;
      if (x.cols() > 0) {
        const Eigen::MatrixXd wx = factor.llt.matrixL().solve(x);
        const Eigen::MatrixXd xtx = wx.transpose() * wx;
        xtx_inverse = xtx.ldlt().solve(Eigen::MatrixXd::Identity(x.cols(), x.cols()));
        beta = xtx_inverse * (wx.transpose() * wd);
        residual = wd - wx * beta;
      }
      const double s2 = residual.squaredNorm() / n;
      const double value = n * std::log(s2) + factor.log_det;
      if (value < best.minus_two_log_l) {
        best.minus_two_log_l = value;
        best.beta = beta;
        // Residual variance with the design's dof, for the coefficients' covariance.
        const double dof = std::max(1.0, n - static_cast<double>(x.cols()));
        best.beta_covariance = xtx_inverse * (residual.squaredNorm() / dof);
        best.k_share = factor.share;
        best.scale2 = s2;
      }
    }
    return best;
  }

  /// k of S0 + k S_K for a grid share (S_K: the covariance of a unit rate random walk).
  double k_of_share(double share) const { return share * scale_; }

 private:
  struct Factor {
    double share;
    Eigen::LLT<Eigen::MatrixXd> llt;
    double log_det;
  };
  Eigen::VectorXd d_;
  std::vector<Factor> factors_;
  double scale_ = 1.0;
};

// The block layout and the covariances of the block-mean differences under `model` (S0) and
// under a unit rate random walk (S_K).
struct BlockSetup {
  std::size_t blocks = 0;
  std::size_t per_block = 0;
  double block_s = 0.0;
  double duration_s = 0.0;
  Eigen::MatrixXd s0;
  Eigen::MatrixXd s_k;
};

BlockSetup block_setup(std::size_t samples, double rate_hz, const NoiseModel& model,
                       std::size_t max_blocks) {
  BlockSetup setup;
  setup.blocks = std::min(max_blocks, samples / kMinBlockSamples);
  if (setup.blocks < kMinBlocks) {
    throw ConfigError(fmt::format(
        "diagnose: {} samples are too few for the time-domain tests ({} blocks of {} samples)",
        samples, kMinBlocks, kMinBlockSamples));
  }
  setup.per_block = samples / setup.blocks;
  setup.block_s = static_cast<double>(setup.per_block) / rate_hz;
  setup.duration_s = static_cast<double>(setup.blocks) * setup.block_s;
  // The stochastic model, nonstationary segments folded into an equivalent stationary one.
  NoiseModel stochastic{model.unit, model.rate_hz, {}};
  for (const auto& term : model.terms) {
    if (!is_deterministic(term_type(term))) stochastic.terms.push_back(term);
  }
  stochastic = stationary_equivalent(stochastic, setup.duration_s).model;
  const std::size_t n = setup.blocks - 1;
  setup.s0 = difference_covariance(n, setup.block_s,
                                   [&](double h) { return phase_covariance(stochastic, h); });
  if (!(setup.s0.diagonal().minCoeff() > 0.0)) {
    // No stochastic level at the block scale: white at the sample level is the null.
    setup.s0 = difference_covariance(n, setup.block_s, [](double h) { return -0.5 * std::abs(h); });
  }
  setup.s_k = difference_covariance(n, setup.block_s,
                                    [](double h) { return std::pow(std::abs(h), 3) / 12.0; });
  return setup;
}

// First differences of the block means of `values`.
Eigen::VectorXd block_differences(const std::vector<double>& values, const BlockSetup& setup) {
  Eigen::VectorXd y(static_cast<Eigen::Index>(setup.blocks));
  for (std::size_t j = 0; j < setup.blocks; ++j) {
    double sum = 0.0;
    for (std::size_t i = 0; i < setup.per_block; ++i) sum += values[j * setup.per_block + i];
    y(static_cast<Eigen::Index>(j)) = sum / static_cast<double>(setup.per_block);
  }
  const auto m = static_cast<Eigen::Index>(setup.blocks);
  return y.tail(m - 1) - y.head(m - 1);
}

// Part of each block after time t (s), and its first differences.
Eigen::VectorXd step_column(double t, std::size_t blocks, double block_s) {
  Eigen::VectorXd f(blocks);
  for (std::size_t j = 0; j < blocks; ++j) {
    const double start = static_cast<double>(j) * block_s;
    f(static_cast<Eigen::Index>(j)) = std::clamp((start + block_s - t) / block_s, 0.0, 1.0);
  }
  return f.tail(blocks - 1) - f.head(blocks - 1);
}

Eigen::MatrixXd with_column(const Eigen::MatrixXd& x, const Eigen::VectorXd& column) {
  Eigen::MatrixXd out(column.size(), x.cols() + 1);
  if (x.cols() > 0) out.leftCols(x.cols()) = x;
  out.col(x.cols()) = column;
  return out;
}

double chi2_quantile(double p) {
  return boost::math::quantile(boost::math::chi_squared_distribution<double>(1.0), p);
}

enum class Kind { kRamp, kStep, kAux };

struct Selected {
  Kind kind;
  std::size_t aux_index = 0;
  double step_time_s = 0.0;
  double statistic = 0.0;
  double threshold = 0.0;
  double k_share = 0.0;
  std::optional<std::array<double, 2>> time_range_s;
};

}  // namespace

std::vector<double> remove_deterministic(const std::vector<double>& rate, double rate_hz,
                                         const std::vector<NoiseTerm>& terms,
                                         const std::vector<AuxChannel>& aux) {
  std::vector<double> out = rate;
  const double tau0 = 1.0 / rate_hz;
  for (const auto& term : terms) {
    if (const auto* ramp = std::get_if<RateRampTerm>(&term)) {
      for (std::size_t k = 0; k < out.size(); ++k) {
        out[k] -= ramp->r * (static_cast<double>(k) + 0.5) * tau0;
      }
    } else if (const auto* step = std::get_if<BiasStepTerm>(&term)) {
      for (std::size_t k = 0; k < out.size(); ++k) {
        const double start = static_cast<double>(k) * tau0;
        out[k] -= step->size * std::clamp((start + tau0 - step->time_s) / tau0, 0.0, 1.0);
      }
    } else if (const auto* sensitivity = std::get_if<AuxSensitivityTerm>(&term)) {
      const auto channel = std::find_if(aux.begin(), aux.end(), [&](const AuxChannel& c) {
        return c.name == sensitivity->column;
      });
      if (channel == aux.end()) {
        throw ConfigError("diagnose: the model's aux_sensitivity term reads the column \"" +
                          sensitivity->column + "\"; pass it with --aux " + sensitivity->column);
      }
      for (std::size_t k = 0; k < out.size() && k < channel->values.size(); ++k) {
        out[k] -= sensitivity->coefficient * channel->values[k];
      }
    }
  }
  return out;
}

RandomWalkTest test_rate_random_walk(const std::vector<double>& rate, double rate_hz,
                                     const NoiseModel& model, double alpha,
                                     std::size_t max_blocks) {
  const BlockSetup setup = block_setup(rate.size(), rate_hz, model, max_blocks);
  const DifferenceModel gls(block_differences(rate, setup), setup.s0, setup.s_k);
  const Eigen::MatrixXd none(static_cast<Eigen::Index>(setup.blocks - 1), 0);
  const GlsFit white = gls.fit(none, false);
  const GlsFit walk = gls.fit(none, true);
  RandomWalkTest test;
  test.blocks = setup.blocks;
  test.block_s = setup.block_s;
  test.statistic = std::max(0.0, white.minus_two_log_l - walk.minus_two_log_l);
  test.threshold = chi2_quantile(1.0 - alpha);
  test.k = std::sqrt(walk.scale2 * gls.k_of_share(walk.k_share));
  test.white_scale = walk.scale2;
  test.minus_two_log_l = white.minus_two_log_l;
  test.significant = test.statistic > test.threshold && walk.k_share > 0.0;
  return test;
}

std::vector<DeterministicFinding> find_deterministic_effects(
    const std::vector<double>& rate, double rate_hz, const NoiseModel& model,
    const std::vector<AuxChannel>& aux, const DeterministicOptions& options) {
  const std::size_t samples = rate.size();
  for (const auto& channel : aux) {
    if (channel.values.size() < samples) {
      throw ConfigError(fmt::format("diagnose: aux channel \"{}\" has {} values for {} samples",
                                    channel.name, channel.values.size(), samples));
    }
  }
  const BlockSetup setup = block_setup(samples, rate_hz, model, options.max_blocks);
  const std::size_t blocks = setup.blocks;
  const double block_s = setup.block_s;
  const double duration_s = setup.duration_s;
  const auto differences = [&](const std::vector<double>& values) {
    return block_differences(values, setup);
  };
  const std::size_t n = blocks - 1;
  const DifferenceModel gls(differences(rate), setup.s0, setup.s_k);

  std::vector<Eigen::VectorXd> aux_columns;
  for (const auto& channel : aux) aux_columns.push_back(differences(channel.values));
  const Eigen::VectorXd ramp_column = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(n), 1.0);

  const double ramp_threshold = chi2_quantile(1.0 - options.alpha);
  const double aux_threshold =
      chi2_quantile(1.0 - options.alpha / static_cast<double>(std::max<std::size_t>(1, aux.size())));
  const double step_threshold = chi2_quantile(1.0 - options.alpha / (4.0 * static_cast<double>(blocks)));

  std::vector<Selected> selected;
  const auto design = [&](const std::vector<Selected>& chosen) {
    Eigen::MatrixXd x(static_cast<Eigen::Index>(n), 0);
    for (const auto& s : chosen) {
      switch (s.kind) {
        case Kind::kRamp:
          x = with_column(x, ramp_column);
          break;
        case Kind::kStep:
          x = with_column(x, step_column(s.step_time_s, blocks, block_s));
          break;
        case Kind::kAux:
          x = with_column(x, aux_columns[s.aux_index]);
          break;
      }
    }
    return x;
  };
  const auto has = [&](Kind kind, std::size_t aux_index) {
    return std::any_of(selected.begin(), selected.end(), [&](const Selected& s) {
      return s.kind == kind && (kind != Kind::kAux || s.aux_index == aux_index);
    });
  };
  // Each round: the information-criterion score -2 ln L + price of every alternative, the
  // stochastic ones (nothing more; a rate random walk, price chi2(1) at alpha) and each
  // deterministic candidate with and without the random walk (price: its threshold). A
  // deterministic candidate is taken when it scores best and its ratio against the same
  // stochastic alternative passes its threshold.
  constexpr int kMaxEffects = 4;
  for (int round = 0; round < kMaxEffects; ++round) {
    const Eigen::MatrixXd x = design(selected);
    const GlsFit null_white = gls.fit(x, false);
    const GlsFit null_walk = gls.fit(x, true);
    const double walk_price = ramp_threshold;
    const double best_stochastic = std::min(null_white.minus_two_log_l,
                                      null_walk.minus_two_log_l + walk_price);
    // Gate: a deterministic candidate must beat every stochastic alternative with its full
    // price (its threshold). Among those that pass, the choice is by likelihood with Akaike's
    // price per parameter (a step has two, its time and size; a ramp or an aux column one): once
    // a step is shown to exist, its Bonferroni price over the scanned times says nothing about
    // whether it is a step or a ramp, and a step half-way explains most of what a ramp does.
    std::optional<Selected> best;
    double best_choice = std::numeric_limits<double>::infinity();
    const auto consider = [&](Selected candidate, const Eigen::VectorXd& column, double threshold) {
      const Eigen::MatrixXd xc = with_column(x, column);
      const double parameters = candidate.kind == Kind::kStep ? 2.0 : 1.0;
      for (bool walk : {false, true}) {
        const GlsFit fit = gls.fit(xc, walk);
        const double ratio =
            (walk ? null_walk : null_white).minus_two_log_l - fit.minus_two_log_l;
        const double walk_cost = walk ? walk_price : 0.0;
        const double score = fit.minus_two_log_l + threshold + walk_cost;
        const double choice = fit.minus_two_log_l + 2.0 * parameters + walk_cost;
        if (ratio > threshold && score < best_stochastic && choice < best_choice) {
          best_choice = choice;
          candidate.statistic = ratio;
          candidate.threshold = threshold;
          candidate.k_share = fit.k_share;
          best = candidate;
        }
      }
    };
    if (options.try_ramp && !has(Kind::kRamp, 0)) {
      consider(Selected{Kind::kRamp}, ramp_column, ramp_threshold);
    }
    for (std::size_t a = 0; a < aux.size(); ++a) {
      if (has(Kind::kAux, a) || !(aux_columns[a].squaredNorm() > 0.0)) continue;
      consider(Selected{Kind::kAux, a}, aux_columns[a], aux_threshold);
    }
    if (options.try_step) {
      // The two-segment scan without the random walk (a lone jump is what a step is; the
      // random-walk alternative is weighed in `consider`): a quarter block, then T/64.
      const auto ratio_at = [&](double t) {
        return null_white.minus_two_log_l -
               gls.fit(with_column(x, step_column(t, blocks, block_s)), false).minus_two_log_l;
      };
      double best_t = 0.0;
      double best_ratio = -std::numeric_limits<double>::infinity();
      for (std::size_t i = 1; i < 4 * (blocks - 1); ++i) {
        const double t = static_cast<double>(i) * block_s / 4.0 + block_s / 2.0;
        if (t >= duration_s - block_s / 2.0) break;
        const double r = ratio_at(t);
        if (r > best_ratio) best_ratio = r, best_t = t;
      }
      std::vector<std::pair<double, double>> profile;
      for (int i = -32; i <= 32; ++i) {
        const double t = best_t + i * block_s / 64.0;
        if (t <= 0.0 || t >= duration_s) continue;
        profile.emplace_back(t, ratio_at(t));
      }
      double fine_t = best_t;
      double fine_ratio = best_ratio;
      for (const auto& [t, r] : profile) {
        if (r > fine_ratio) fine_ratio = r, fine_t = t;
      }
      // 1-sigma interval: where the ratio is within 1 of its maximum (at least one grid step).
      double lo = fine_t - block_s / 64.0;
      double hi = fine_t + block_s / 64.0;
      for (const auto& [t, r] : profile) {
        if (r >= fine_ratio - 1.0) lo = std::min(lo, t), hi = std::max(hi, t);
      }
      // Several steps may exist; a second one at the same time is no new effect.
      const bool same = std::any_of(selected.begin(), selected.end(), [&](const Selected& s) {
        return s.kind == Kind::kStep && std::abs(s.step_time_s - fine_t) < block_s;
      });
      if (!same) {
        Selected s{Kind::kStep};
        s.step_time_s = fine_t;
        s.time_range_s = std::array<double, 2>{lo, hi};
        consider(s, step_column(fine_t, blocks, block_s), step_threshold);
      }
    }
    if (!best) break;
    selected.push_back(*best);
  }

  // Joint refit of all selected effects.
  std::vector<DeterministicFinding> findings;
  if (selected.empty()) return findings;
  const Eigen::MatrixXd joint_design = design(selected);
  const GlsFit joint_white = gls.fit(joint_design, false);
  const GlsFit joint_walk = gls.fit(joint_design, true);
  const GlsFit& joint =
      joint_walk.minus_two_log_l + ramp_threshold < joint_white.minus_two_log_l ? joint_walk
                                                                               : joint_white;
  for (std::size_t i = 0; i < selected.size(); ++i) {
    const Selected& s = selected[i];
    const auto index = static_cast<Eigen::Index>(i);
    const double value = joint.beta(index);
    const double sigma = std::sqrt(std::max(0.0, joint.beta_covariance(index, index)));
    DeterministicFinding finding;
    finding.statistic = s.statistic;
    finding.threshold = s.threshold;
    finding.random_walk_share = s.k_share;
    const std::string test = fmt::format(
        "likelihood ratio {:.1f} against {:.1f} (alpha {:.0e}) over {} block means of {:.4g} s, "
        "a free white level and rate random walk profiled out",
        s.statistic, s.threshold, options.alpha, blocks, block_s);
    switch (s.kind) {
      case Kind::kRamp: {
        finding.term = RateRampTerm{value / block_s};
        finding.sigma = {{"R", sigma / block_s}};
        finding.evidence = "The block means drift linearly with time: " + test + ".";
        break;
      }
      case Kind::kStep: {
        finding.term = BiasStepTerm{s.step_time_s, value};
        const double half = (s.time_range_s->at(1) - s.time_range_s->at(0)) / 2.0;
        finding.sigma = {{"time_s", half}, {"size", sigma}};
        finding.time_range_s = s.time_range_s;
        finding.evidence =
            fmt::format("The block means jump at t = {:.1f} s (two-segment {}).", s.step_time_s,
                        test);
        break;
      }
      case Kind::kAux: {
        AuxSensitivityTerm term;
        term.column = aux[s.aux_index].name;
        term.coefficient = value;
        finding.term = term;
        finding.sigma = {{"coefficient", sigma}};
        finding.evidence = fmt::format("The block means follow the auxiliary channel \"{}\": {}.",
                                       term.column, test);
        break;
      }
    }
    findings.push_back(std::move(finding));
  }
  return findings;
}

}  // namespace stochnav

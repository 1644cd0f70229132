#include "stochnav/sim/flicker_bank.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "stochnav/model/closed_forms.hpp"

namespace stochnav {
namespace {

constexpr double kLowestTauOverTau0 = 0.1;
constexpr double kHighestTauOverBand = 3.0;
constexpr double kFitTausPerDecade = 20.0;

// Lawson-Hanson active-set non-negative least squares: min |A w - b| subject to w >= 0.
Eigen::VectorXd non_negative_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  const Eigen::Index n = a.cols();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  std::vector<bool> active(static_cast<std::size_t>(n), false);
  for (Eigen::Index outer = 0; outer < 3 * n; ++outer) {
    const Eigen::VectorXd gradient = a.transpose() * (b - a * w);
    Eigen::Index entering = -1;
    double best = 1e-12 * gradient.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!active[static_cast<std::size_t>(i)] && gradient[i] > best) {
        best = gradient[i];
        entering = i;
      }
    }
    if (entering < 0) break;
    active[static_cast<std::size_t>(entering)] = true;
    while (true) {
      std::vector<Eigen::Index> index;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (active[static_cast<std::size_t>(i)]) index.push_back(i);
      }
      Eigen::MatrixXd sub(a.rows(), static_cast<Eigen::Index>(index.size()));
      for (std::size_t k = 0; k < index.size(); ++k) {
        sub.col(static_cast<Eigen::Index>(k)) = a.col(index[k]);
      }
      const Eigen::VectorXd z = sub.colPivHouseholderQr().solve(b);
      if ((z.array() > 0.0).all()) {
        w.setZero();
        for (std::size_t k = 0; k < index.size(); ++k)
          w[index[k]] = z[static_cast<Eigen::Index>(k)];
        break;
      }
      // Step back to the feasible boundary and drop the components that reach zero.
      double step = 1.0;
      for (std::size_t k = 0; k < index.size(); ++k) {
        const double zk = z[static_cast<Eigen::Index>(k)];
        if (zk <= 0.0) step = std::min(step, w[index[k]] / (w[index[k]] - zk));
      }
      for (std::size_t k = 0; k < index.size(); ++k) {
        w[index[k]] += step * (z[static_cast<Eigen::Index>(k)] - w[index[k]]);
      }
      for (Eigen::Index i = 0; i < n; ++i) {
        if (active[static_cast<std::size_t>(i)] && w[i] <= 1e-15) {
          active[static_cast<std::size_t>(i)] = false;
          w[i] = 0.0;
        }
      }
    }
  }
  return w;
}

std::vector<double> log_spaced(double low, double high, std::size_t count) {
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double fraction =
        count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
    values[i] = low * std::pow(high / low, fraction);
  }
  return values;
}

std::size_t points_for(double low, double high, double per_decade) {
  return static_cast<std::size_t>(std::ceil(std::log10(high / low) * per_decade)) + 1;
}

}  // namespace

FlickerBank design_flicker_bank(double b, double tau0_s, double band_max_s,
                                double components_per_decade) {
  FlickerBank bank;
  bank.band_min_s = tau0_s;
  bank.band_max_s = std::max(band_max_s, tau0_s);
  if (!(b > 0.0)) return bank;

  const double lowest = kLowestTauOverTau0 * tau0_s;
  const double highest = kHighestTauOverBand * bank.band_max_s;
  const auto tau_c =
      log_spaced(lowest, highest, points_for(lowest, highest, components_per_decade));
  // Fit in units of the floor: unit-variance components, target AVAR 1.
  const std::size_t fit_count =
      std::max<std::size_t>(points_for(tau0_s, bank.band_max_s, kFitTausPerDecade), 2);
  const auto fit_tau = log_spaced(tau0_s, bank.band_max_s, fit_count);
  Eigen::MatrixXd design(static_cast<Eigen::Index>(fit_tau.size()),
                         static_cast<Eigen::Index>(tau_c.size()));
  for (std::size_t j = 0; j < fit_tau.size(); ++j) {
    for (std::size_t k = 0; k < tau_c.size(); ++k) {
      design(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(k)) =
          closed_form::gauss_markov_avar(1.0, tau_c[k], fit_tau[j]);
    }
  }
  const Eigen::VectorXd weight = non_negative_least_squares(
      design, Eigen::VectorXd::Ones(static_cast<Eigen::Index>(fit_tau.size())));

  const double floor = closed_form::bias_instability_avar(b);
  for (std::size_t k = 0; k < tau_c.size(); ++k) {
    const double w = weight[static_cast<Eigen::Index>(k)];
    if (w <= 0.0) continue;
    bank.tau_c_s.push_back(tau_c[k]);
    bank.sigma.push_back(std::sqrt(w * floor));
  }
  // Achieved flatness on a grid four times denser than the fit.
  for (double tau : log_spaced(tau0_s, bank.band_max_s, 4 * fit_count)) {
    bank.max_relative_ripple = std::max(
        bank.max_relative_ripple, std::abs(flicker_bank_allan_variance(bank, tau) / floor - 1.0));
  }
  return bank;
}

double flicker_bank_allan_variance(const FlickerBank& bank, double tau_s) {
  double sum = 0.0;
  for (std::size_t k = 0; k < bank.tau_c_s.size(); ++k) {
    sum += closed_form::gauss_markov_avar(bank.sigma[k], bank.tau_c_s[k], tau_s);
  }
  return sum;
}

}  // namespace stochnav

#include "stochnav/diagnose/innovation_aux.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>

#include <Eigen/Dense>

namespace stochnav {
namespace {

double interpolate(const TimedChannel& channel, double t) {
  if (channel.values.empty()) return 0.0;
  const double x = (t - channel.t0_s) * channel.rate_hz;
  if (x <= 0.0) return channel.values.front();
  const auto last = static_cast<double>(channel.values.size() - 1);
  if (x >= last) return channel.values.back();
  const auto i = static_cast<std::size_t>(x);
  const double f = x - static_cast<double>(i);
  return channel.values[i] * (1.0 - f) + channel.values[i + 1] * f;
}

struct SlopeFit {
  double slope = 0.0, sigma = 0.0, t = 0.0, dof = 0.0;
};

// OLS of y on x (columns include the intercept); the slope is coefficient 1. Residual scale
// with an effective block count from the residuals' lag-1 autocorrelation.
SlopeFit fit_slope(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  SlopeFit fit;
  const Eigen::MatrixXd xtx = x.transpose() * x;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(xtx);
  const Eigen::VectorXd beta = ldlt.solve(x.transpose() * y);
  const Eigen::VectorXd r = y - x * beta;
  const auto n = static_cast<double>(y.size());
  double r1 = 0.0;
  if (r.squaredNorm() > 0.0) {
    r1 = r.head(r.size() - 1).dot(r.tail(r.size() - 1)) / r.squaredNorm();
  }
  r1 = std::clamp(r1, 0.0, 0.95);
  const double inflation = (1.0 + r1) / (1.0 - r1);
  const double p = static_cast<double>(x.cols());
  fit.dof = std::max(1.0, n / inflation - p);
  const double s2 = r.squaredNorm() / std::max(1.0, n - p) * inflation;
  const Eigen::MatrixXd covariance = ldlt.solve(Eigen::MatrixXd::Identity(x.cols(), x.cols())) * s2;
  fit.slope = beta(1);
  fit.sigma = std::sqrt(std::max(0.0, covariance(1, 1)));
  fit.t = fit.sigma > 0.0 ? fit.slope / fit.sigma : 0.0;
  return fit;
}

}  // namespace

std::vector<InnovationAuxFinding> innovation_aux_findings(
    const std::vector<AidInnovations>& innovations, const InnovationAnalysis& analysis,
    const std::vector<TimedChannel>& channels, double alpha) {
  std::vector<InnovationAuxFinding> findings;
  std::size_t tests = 0;
  for (const auto& aid : innovations) {
    if (!aid.samples.empty()) tests += aid.samples.front().z.size() * channels.size();
  }
  if (tests == 0) return findings;
  const double level = alpha / static_cast<double>(tests);
  for (std::size_t a = 0; a < innovations.size(); ++a) {
    const AidInnovations& aid = innovations[a];
    if (aid.samples.empty()) continue;
    const std::size_t components = aid.samples.front().z.size();
    for (std::size_t i = 0; i < components; ++i) {
      std::vector<double> times, u;
      for (const auto& s : aid.samples) {
        if (!s.accepted || i >= s.z.size() || !(s.sigma[i] > 0.0)) continue;
        times.push_back(s.t_s);
        u.push_back(s.z[i] / s.sigma[i]);
      }
      const std::size_t blocks = std::min<std::size_t>(32, u.size() / 4);
      if (blocks < 8) continue;
      const std::size_t per = u.size() / blocks;
      for (const TimedChannel& channel : channels) {
        Eigen::VectorXd y(blocks), c(blocks), t(blocks);
        for (std::size_t b = 0; b < blocks; ++b) {
          double su = 0.0, sc = 0.0, st = 0.0;
          for (std::size_t k = b * per; k < (b + 1) * per; ++k) {
            su += u[k];
            sc += interpolate(channel, times[k]);
            st += times[k];
          }
          const auto idx = static_cast<Eigen::Index>(b);
          y(idx) = su / static_cast<double>(per);
          c(idx) = sc / static_cast<double>(per);
          t(idx) = st / static_cast<double>(per);
        }
        if (!((c.array() - c.mean()).square().sum() > 0.0)) continue;
        Eigen::MatrixXd x(blocks, 2);
        x.col(0).setOnes();
        x.col(1) = c;
        const SlopeFit fit = fit_slope(x, y);
        const boost::math::students_t_distribution<double> student(fit.dof);
        const double p = 2.0 * boost::math::cdf(boost::math::complement(student, std::abs(fit.t)));
        if (!(p < level)) continue;
        Eigen::MatrixXd xt(blocks, 3);
        xt.col(0).setOnes();
        xt.col(1) = c;
        xt.col(2) = t.array() - t.mean();
        const SlopeFit with_time = fit_slope(xt, y);
        InnovationAuxFinding finding;
        finding.aid_index = aid.aid_index;
        finding.aid_type = aid.type;
        finding.component = a < analysis.aids.size() && i < analysis.aids[a].components.size()
                                ? analysis.aids[a].components[i].name
                                : fmt::format("component {}", i);
        finding.column = channel.name;
        finding.slope = fit.slope;
        finding.slope_sigma = fit.sigma;
        finding.t_statistic = fit.t;
        finding.p_value = p;
        finding.t_with_time = with_time.t;
        finding.evidence = fmt::format(
            "The normalised innovation of {} ({}) drifts with {}: slope {:.3g} +/- {:.2g} per "
            "unit over {} block means (t = {:.1f}, p = {:.2g} < {:.2g}, Bonferroni over {} "
            "tests); with time as a second regressor t = {:.1f}{}. A bias that depends on {} "
            "(aux_sensitivity) is likely; diagnose the sensor's record with --aux {}.",
            finding.component, aid.type, channel.name, fit.slope, fit.sigma, blocks, fit.t, p,
            level, tests, with_time.t,
            std::abs(with_time.t) < 2.0 ? " (the channel and a plain drift in time cannot be "
                                          "told apart on this run)"
                                        : "",
            channel.name, channel.name);
        findings.push_back(std::move(finding));
      }
    }
  }
  return findings;
}

}  // namespace stochnav

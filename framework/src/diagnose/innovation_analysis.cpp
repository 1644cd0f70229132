// Innovation-based consistency of a filter run (diagnose/innovation_analysis.hpp).

#include "stochnav/diagnose/innovation_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <numeric>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

constexpr std::size_t kMinimumUpdates = 20;

struct ComponentMeaning {
  std::string name;
  std::string sensor;
};

// What each component of the bundled aids measures, and which sensor errors it reveals first.
ComponentMeaning component_meaning(const std::string& aid_type, std::size_t index) {
  static const char* kAxes[] = {"E", "N", "U"};
  const std::string horizontal = "gyro tilt (g x phi) or horizontal accelerometer";
  const std::string vertical = "vertical accelerometer";
  if ((aid_type == "static_position" && index < 6) || (aid_type == "position_fix" && index < 3)) {
    const bool position = index < 3;
    const std::size_t axis = index % 3;
    return {fmt::format("{} {} ({})", position ? "position" : "velocity", kAxes[axis],
                        position ? "m" : "m/s"),
            axis < 2 ? horizontal : vertical};
  }
  if (aid_type == "zupt" && index < 3) {
    return {fmt::format("velocity {} (m/s)", kAxes[index]), index < 2 ? horizontal : vertical};
  }
  if (aid_type == "rop" && index < 3) {
    static const char* kBody[] = {"x", "y", "z (along hole)"};
    return {fmt::format("body velocity {} (m/s)", kBody[index]),
            index < 2 ? "gyro (attitude) or cross-axis accelerometers" : "axial accelerometer"};
  }
  if (aid_type == "pipe_length" && index == 0) {
    return {"along-hole speed (m/s)", "axial accelerometer or depth measurement"};
  }
  return {fmt::format("component {}", index), "unknown (aid type " + aid_type + ")"};
}

// The upper median (the larger middle value of an even count): a robust level, no averaging.
double upper_median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Autocorrelation of a zero-mean (under the model) sequence at lags 1..max_lag, about zero, not
// about the sample mean: a bias in u is part of what the test must see.
std::vector<double> autocorrelation(const std::vector<double>& u, int max_lag) {
  const double energy = std::inner_product(u.begin(), u.end(), u.begin(), 0.0);
  std::vector<double> rho(static_cast<std::size_t>(max_lag), 0.0);
  if (energy <= 0.0) return rho;
  for (int lag = 1; lag <= max_lag && static_cast<std::size_t>(lag) < u.size(); ++lag) {
    double sum = 0.0;
    for (std::size_t t = static_cast<std::size_t>(lag); t < u.size(); ++t) {
      sum += u[t] * u[t - static_cast<std::size_t>(lag)];
    }
    rho[static_cast<std::size_t>(lag - 1)] = sum / energy;
  }
  return rho;
}

double effective_terms(std::size_t n, double rho1) {
  const double rho = std::clamp(rho1, 0.0, 0.995);
  const double r2 = rho * rho;
  return std::max(1.0, static_cast<double>(n) * (1.0 - r2) / (1.0 + r2));
}

ComponentStatistics component_statistics(const std::vector<double>& u, int max_lag, double alpha,
                                         std::size_t components) {
  ComponentStatistics stats;
  const double n = static_cast<double>(u.size());
  stats.level = std::inner_product(u.begin(), u.end(), u.begin(), 0.0) / n;
  const int lags = std::max(1, std::min(max_lag, static_cast<int>(u.size()) / 5));
  stats.autocorrelation = autocorrelation(u, lags);
  stats.rho1 = stats.autocorrelation.front();
  double q = 0.0;
  for (int k = 1; k <= lags; ++k) {
    const double r = stats.autocorrelation[static_cast<std::size_t>(k - 1)];
    q += r * r / (n - k);
  }
  q *= n * (n + 2.0);
  stats.ljung_box_p = boost::math::cdf(
      boost::math::complement(boost::math::chi_squared_distribution<double>(lags), q));
  stats.effective_terms = effective_terms(u.size(), stats.rho1);
  // Bonferroni over the components of the aid, two-sided.
  const double tail = alpha / (2.0 * static_cast<double>(components));
  const boost::math::chi_squared_distribution<double> chi2(stats.effective_terms);
  stats.level_lo = boost::math::quantile(chi2, tail) / stats.effective_terms;
  stats.level_hi = boost::math::quantile(chi2, 1.0 - tail) / stats.effective_terms;
  return stats;
}

struct SeriesView {
  std::vector<double> t;
  std::vector<std::vector<double>> u;  // per component
};

SeriesView normalised_series(const AidInnovations& aid) {
  SeriesView view;
  const std::size_t m = aid.samples.front().z.size();
  view.u.assign(m, {});
  for (const auto& s : aid.samples) {
    if (s.z.size() != m || !std::isfinite(s.nis)) continue;  // singular S: no information
    bool usable = true;
    for (std::size_t i = 0; i < m; ++i) usable &= s.sigma[i] > 0.0;
    if (!usable) continue;
    view.t.push_back(s.t_s);
    for (std::size_t i = 0; i < m; ++i) view.u[i].push_back(s.z[i] / s.sigma[i]);
  }
  return view;
}

std::vector<LevelWindow> level_windows(const SeriesView& view, double window_s,
                                       std::vector<std::vector<double>>& terms) {
  std::vector<LevelWindow> windows;
  const std::size_t m = view.u.size();
  const double start = window_s * std::floor(view.t.front() / window_s);
  std::size_t first = 0;
  while (first < view.t.size()) {
    const double t0 = start + window_s * std::floor((view.t[first] - start) / window_s);
    const double t1 = t0 + window_s;
    std::size_t last = first;
    while (last < view.t.size() && view.t[last] < t1) ++last;
    LevelWindow window{t0, t1, std::vector<double>(m, 0.0), std::vector<int>(m, 0)};
    std::vector<double> count(m, 0.0);
    for (std::size_t i = 0; i < m; ++i) {
      for (std::size_t k = first; k < last; ++k) window.level[i] += view.u[i][k] * view.u[i][k];
      window.level[i] /= static_cast<double>(last - first);
      count[i] = static_cast<double>(last - first);
    }
    windows.push_back(window);
    terms.push_back(count);
    first = last;
  }
  return windows;
}

// Runs of consecutive windows flagged +1 in any component.
struct FlaggedSpan {
  std::size_t first = 0, last = 0;  // windows [first, last]
};

std::vector<FlaggedSpan> high_spans(const std::vector<LevelWindow>& windows) {
  std::vector<FlaggedSpan> spans;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    const bool high =
        std::find(windows[w].flag.begin(), windows[w].flag.end(), 1) != windows[w].flag.end();
    if (!high) continue;
    if (!spans.empty() && spans.back().last + 1 == w) {
      spans.back().last = w;
    } else {
      spans.push_back({w, w});
    }
  }
  return spans;
}

std::string join(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// The sensor named by a set of components: their hints, without repeats.
std::string sensor_of(const AidAnalysis& aid, const std::vector<std::size_t>& components) {
  std::vector<std::string> hints;
  for (std::size_t i : components) {
    const auto& hint = aid.components[i].sensor_hint;
    if (std::find(hints.begin(), hints.end(), hint) == hints.end()) hints.push_back(hint);
  }
  return join(hints);
}

std::vector<std::string> names_of(const AidAnalysis& aid,
                                  const std::vector<std::size_t>& components) {
  std::vector<std::string> names;
  for (std::size_t i : components) names.push_back(aid.components[i].name);
  return names;
}

// Sign changes of the autocorrelation beyond its white-noise spread: a periodic error.
std::optional<double> oscillation_period(const std::vector<double>& rho, double n, double dt) {
  const double significant = 2.0 / std::sqrt(n);
  std::vector<double> crossings;
  for (std::size_t k = 1; k < rho.size(); ++k) {
    if ((rho[k - 1] > significant && rho[k] < -significant) ||
        (rho[k - 1] < -significant && rho[k] > significant) ||
        (rho[k - 1] * rho[k] < 0.0 &&
         std::max(std::abs(rho[k - 1]), std::abs(rho[k])) > 2.0 * significant)) {
      crossings.push_back(static_cast<double>(k) + rho[k - 1] / (rho[k - 1] - rho[k]));
    }
  }
  if (crossings.size() < 2) return std::nullopt;
  const double spacing =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  return 2.0 * spacing * dt;
}

// Names the effect behind a component that is too high or not white over the whole run.
InnovationFinding name_persistent_effect(const AidAnalysis& aid, std::size_t i, double alpha) {
  const ComponentStatistics& c = aid.components[i];
  InnovationFinding finding;
  finding.aid_type = aid.type;
  finding.components = {c.name};
  finding.sensor = c.sensor_hint;
  finding.scale = std::sqrt(c.level);
  const bool white = c.ljung_box_p >= alpha;
  const double n = static_cast<double>(aid.updates);
  const double last = c.autocorrelation.back();
  if (white) {
    finding.effect = "angle_random_walk";
    finding.evidence = fmt::format(
        "{}: mean u^2 = {:.3g} above its band [{:.3g}, {:.3g}] and white (Ljung-Box p = {:.2g}): "
        "white noise understated by a factor of about {:.2g} in standard deviation",
        c.name, c.level, c.level_lo, c.level_hi, c.ljung_box_p, finding.scale);
  } else if (const auto period = oscillation_period(c.autocorrelation, n, aid.update_interval_s)) {
    finding.effect = "sinusoid";
    finding.period_s = *period;
    finding.evidence = fmt::format(
        "{}: autocorrelation changes sign periodically (apparent period {:.3g} s at the aid "
        "interval {:.3g} s; the true line may be aliased), Ljung-Box p = {:.2g}",
        c.name, *period, aid.update_interval_s, c.ljung_box_p);
  } else if (c.rho1 > 0.0 && last > 0.8 * c.rho1 && c.rho1 > 0.9) {
    finding.effect = "rate_random_walk";
    finding.evidence = fmt::format(
        "{}: autocorrelation {:.3g} at lag 1 and still {:.3g} at lag {}: a wandering error "
        "(random walk of the bias), mean u^2 = {:.3g}",
        c.name, c.rho1, last, c.autocorrelation.size(), c.level);
  } else {
    finding.effect = "gauss_markov";
    if (c.rho1 > 0.0 && c.rho1 < 1.0) {
      finding.tau_c_s = -aid.update_interval_s / std::log(c.rho1);
    }
    finding.evidence = fmt::format(
        "{}: correlated innovations (lag-1 autocorrelation {:.3g}, Ljung-Box p = {:.2g}) "
        "decaying over the lags{}; mean u^2 = {:.3g} (band [{:.3g}, {:.3g}])",
        c.name, c.rho1, c.ljung_box_p,
        finding.tau_c_s ? fmt::format(": correlation time about {:.3g} s", *finding.tau_c_s)
                        : std::string(),
        c.level, c.level_lo, c.level_hi);
  }
  return finding;
}

AidAnalysis analyse_aid(const AidInnovations& input, const InnovationAnalysisOptions& options,
                        std::vector<InnovationFinding>& findings) {
  AidAnalysis aid;
  aid.aid_index = input.aid_index;
  aid.type = input.type;
  const SeriesView view = normalised_series(input);
  aid.updates = view.t.size();
  const std::size_t m = view.u.size();
  for (std::size_t i = 0; i < m; ++i) {
    ComponentStatistics stats;
    const auto meaning = component_meaning(input.type, i);
    stats.name = meaning.name;
    stats.sensor_hint = meaning.sensor;
    aid.components.push_back(stats);
  }
  if (aid.updates < kMinimumUpdates) return aid;
  std::vector<double> spacing;
  for (std::size_t k = 1; k < view.t.size(); ++k) spacing.push_back(view.t[k] - view.t[k - 1]);
  aid.update_interval_s = upper_median(spacing);

  for (std::size_t i = 0; i < m; ++i) {
    const auto meaning = component_meaning(input.type, i);
    aid.components[i] = component_statistics(view.u[i], options.max_lag, options.alpha, m);
    aid.components[i].name = meaning.name;
    aid.components[i].sensor_hint = meaning.sensor;
  }

  // Levels over time against the median window, F test with the windows' effective terms.
  std::vector<std::vector<double>> terms;
  aid.windows = level_windows(view, options.window_s, terms);
  const std::size_t n_windows = aid.windows.size();
  aid.reference_level.assign(m, 0.0);
  if (n_windows >= 3) {
    const double tail = options.alpha / (2.0 * static_cast<double>(n_windows * m));
    for (std::size_t i = 0; i < m; ++i) {
      std::vector<double> levels;
      for (const auto& w : aid.windows) levels.push_back(w.level[i]);
      const double reference = upper_median(levels);
      aid.reference_level[i] = reference;
      if (reference <= 0.0) continue;
      const double rho = aid.components[i].rho1;
      const double nu_ref = effective_terms(aid.updates, rho);
      for (std::size_t w = 0; w < n_windows; ++w) {
        const double nu_w = effective_terms(static_cast<std::size_t>(terms[w][i]), rho);
        const boost::math::fisher_f_distribution<double> f(nu_w, nu_ref);
        const double ratio = aid.windows[w].level[i] / reference;
        if (ratio > boost::math::quantile(f, 1.0 - tail)) aid.windows[w].flag[i] = 1;
        if (ratio < boost::math::quantile(f, tail)) aid.windows[w].flag[i] = -1;
      }
    }
  }

  // Time-localised rises: the nonstationary effect, one finding per span.
  std::vector<bool> in_span(n_windows, false);
  for (const FlaggedSpan& span : high_spans(aid.windows)) {
    std::vector<std::size_t> components;
    std::vector<double> ratios;
    for (std::size_t i = 0; i < m; ++i) {
      bool high = false;
      double level = 0.0, count = 0.0;
      for (std::size_t w = span.first; w <= span.last; ++w) {
        high |= aid.windows[w].flag[i] == 1;
        level += aid.windows[w].level[i] * terms[w][i];
        count += terms[w][i];
      }
      if (!high) continue;
      components.push_back(i);
      ratios.push_back(level / count / aid.reference_level[i]);
    }
    for (std::size_t w = span.first; w <= span.last; ++w) in_span[w] = true;
    InnovationFinding finding;
    finding.effect = "nonstationary";
    finding.aid_type = aid.type;
    finding.components = names_of(aid, components);
    finding.sensor = sensor_of(aid, components);
    finding.time_range_s = std::pair{aid.windows[span.first].t0_s, aid.windows[span.last].t1_s};
    finding.scale = std::sqrt(upper_median(ratios));
    finding.evidence = fmt::format(
        "innovation level (median over the components) {:.3g} times the run's median level over "
        "[{:.0f}, {:.0f}) s in {} "
        "(F test over {} windows of {:.0f} s, alpha {}): the noise rose over that span",
        finding.scale * finding.scale, finding.time_range_s->first, finding.time_range_s->second,
        join(finding.components), n_windows, options.window_s, options.alpha);
    findings.push_back(finding);
  }

  // Persistent disagreement over the rest of the run.
  std::vector<std::size_t> overstated;
  for (std::size_t i = 0; i < m; ++i) {
    const ComponentStatistics& c = aid.components[i];
    // The level outside the nonstationary spans, against the whole-run band.
    double level = 0.0, count = 0.0;
    for (std::size_t w = 0; w < n_windows; ++w) {
      if (in_span[w]) continue;
      level += aid.windows[w].level[i] * terms[w][i];
      count += terms[w][i];
    }
    level = count > 0.0 ? level / count : c.level;
    const bool white = c.ljung_box_p >= options.alpha;
    if (level > c.level_hi || (!white && level >= c.level_lo)) {
      findings.push_back(name_persistent_effect(aid, i, options.alpha));
    } else if (level < c.level_lo) {
      overstated.push_back(i);
    }
  }
  if (!overstated.empty()) {
    InnovationFinding finding;
    finding.aid_type = aid.type;
    finding.components = names_of(aid, overstated);
    finding.sensor = sensor_of(aid, overstated);
    std::string levels;
    for (std::size_t i : overstated) {
      levels += fmt::format("{}{:.3g}", levels.empty() ? "" : ", ", aid.components[i].level);
    }
    finding.scale = std::sqrt(aid.components[overstated.front()].level);
    finding.evidence = fmt::format(
        "mean u^2 below its band in {} ({}): the model or the aid's R overstates the noise "
        "(conservative, not a missing effect)",
        join(finding.components), levels);
    findings.push_back(finding);
  }
  return aid;
}

}  // namespace

std::string InnovationAnalysisOptions::validate() const {
  if (!(window_s > 0.0)) return fmt::format("--window-s {}: use a window > 0 s", window_s);
  if (!(alpha > 0.0 && alpha < 0.5)) return fmt::format("--alpha {}: use 0 < alpha < 0.5", alpha);
  if (max_lag < 1) return fmt::format("--max-lag {}: use at least 1 lag", max_lag);
  return {};
}

InnovationAnalysis analyse_innovations(const std::vector<AidInnovations>& aids,
                                       const InnovationAnalysisOptions& options) {
  if (const auto problem = options.validate(); !problem.empty()) throw ConfigError(problem);
  InnovationAnalysis analysis;
  for (const auto& aid : aids) {
    if (aid.samples.empty()) continue;
    analysis.aids.push_back(analyse_aid(aid, options, analysis.findings));
  }
  analysis.consistent = std::none_of(analysis.findings.begin(), analysis.findings.end(),
                                     [](const auto& f) { return f.effect.has_value(); });
  return analysis;
}

}  // namespace stochnav

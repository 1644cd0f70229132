#include "fit_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "stochnav/fit/fit_result_json.hpp"
#include "stochnav/model/noise_term.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav::cli {
namespace {

/// One fitted parameter in reporting units.
struct ReportedParameter {
  std::string term;
  std::string name;
  std::string unit;
  double value = 0.0;
  double sigma = 0.0;
};

std::vector<ReportedParameter> reported_parameters(const FitResult& fit) {
  const Quantity quantity = quantity_of(fit.model.unit);
  std::vector<ReportedParameter> out;
  for (std::size_t t = 0; t < fit.model.terms.size(); ++t) {
    const NoiseTerm& term = fit.model.terms[t];
    const auto specs = parameter_specs(term_type(term));
    for (std::size_t p = 0; p < specs.size(); ++p) {
      const auto value = parameter_value(term, p);
      if (!value) continue;
      const auto sigma = t < fit.sigma.size() ? parameter_value(fit.sigma[t], p) : std::nullopt;
      out.push_back({std::string(term_type_name(term_type(term))), std::string(specs[p].name),
                     reported_unit_name(quantity, specs[p].dimension),
                     to_reported(quantity, specs[p].dimension, *value),
                     sigma ? to_reported(quantity, specs[p].dimension, *sigma) : std::nan("")});
    }
  }
  return out;
}

std::string readoff_rows(const FitResult& fit, bool csv) {
  const Quantity quantity = quantity_of(fit.model.unit);
  const auto& r = fit.diagnostics.readoffs;
  struct Row {
    const char* term;
    const char* name;
    ParameterDimension dimension;
    SlopeReadoff readoff;
  };
  const Row rows[] = {
      {"quantization", "Q", ParameterDimension::kAngle, r.quantization},
      {"angle_random_walk", "N", ParameterDimension::kAnglePerRootTime, r.angle_random_walk},
      {"bias_instability", "B", ParameterDimension::kRate, r.bias_instability},
      {"rate_random_walk", "K", ParameterDimension::kRatePerRootTime, r.rate_random_walk},
      {"rate_ramp", "R", ParameterDimension::kRatePerTime, r.rate_ramp},
  };
  std::string out;
  for (const Row& row : rows) {
    const double value = to_reported(quantity, row.dimension, row.readoff.value);
    const std::string unit = reported_unit_name(quantity, row.dimension);
    out += csv ? fmt::format("slope_readoff,{},{},{:.6g},,{}\n", row.term, row.name, value, unit)
               : fmt::format("  {:<18} {:<2} = {:<12.5g} {:<16} (line touches the curve at tau = "
                             "{:.4g} s)\n",
                             row.term, row.name, value, unit, row.readoff.tau_s);
  }
  return out;
}

}  // namespace

std::string format_fit(const FitResult& fit, const Record& record, std::size_t samples,
                       OutputFormat format) {
  if (format == OutputFormat::kJson) return fit_result_to_json(fit).dump(2) + "\n";
  const auto parameters = reported_parameters(fit);
  if (format == OutputFormat::kCsv) {
    std::string out = "kind,term,parameter,value,sigma,unit\n";
    for (const auto& p : parameters) {
      out += fmt::format("fit,{},{},{:.6g},{:.3g},{}\n", p.term, p.name, p.value, p.sigma, p.unit);
    }
    return fit.diagnostics.method == FitMethod::kAvar ? out + readoff_rows(fit, true) : out;
  }
  const auto& d = fit.diagnostics;
  std::string out = fmt::format(
      "# noise-term fit of {} [{}] ({} samples at {} Hz, unit {})\n", record.source, record.column,
      samples, record.rate_hz, unit_name(record.unit));
  if (d.method == FitMethod::kGmwm) {
    out += fmt::format("# GMWM on the Haar wavelet variance: {} scales, {} parameters; objective "
                       "{:.4g} (J-test p = {:.3g}); WIC {:.4g}\n",
                       d.points, d.parameters, d.cost, d.chi_square_p_value(), d.criterion_value);
    out += fmt::format("# Gauss-Markov terms sampled as {}\n",
                       d.gauss_markov_sampling == GaussMarkovSampling::kPoint
                           ? "point samples (discrete AR1, phi = exp(-tau0 / tau_c))"
                           : "interval means");
    for (const auto& model : fit.ranking) {
      std::string names;
      for (TermType type : model.terms) {
        names += (names.empty() ? "" : "+") + std::string(term_type_name(type));
      }
      out += fmt::format("#   rank: {:<60} WIC {:<12.5g} objective {:.5g}{}{}\n", names,
                         model.wic, model.objective, model.failed ? " FAILED" : "",
                         model.dropped_terms.empty() ? "" : " (dropped a term on its bound)");
    }
  } else {
    out += fmt::format("# terms {}; robust loss {} (scale {}); {} points, {} parameters; "
                       "chi-square {:.3g}; {} {:.4g}\n",
                       d.automatic ? fmt::format("chosen by {}", criterion_name(d.criterion))
                                   : std::string("given by --terms"),
                       robust_loss_name(d.loss), d.loss_scale, d.points, d.parameters,
                       d.chi_square, criterion_name(d.criterion), d.criterion_value);
  }
  for (const auto& p : parameters) {
    out += fmt::format("  {:<18} {:<12} = {:<12.5g} +/- {:<10.3g} {}\n", p.term, p.name, p.value,
                       p.sigma, p.unit);
  }
  if (d.method == FitMethod::kAvar) {
    out += "# IEEE 952 slope read-offs (cross-check):\n" + readoff_rows(fit, false);
  }
  for (const auto& warning : d.warnings) out += "# warning: " + warning + "\n";
  for (const auto& term : d.dropped_terms) out += "# dropped term: " + term + "\n";
  if (d.failed()) out += "# FIT FAILED: " + d.failure() + "\n";
  return out;
}

std::string format_windowed_fit(const std::vector<double>& time_s,
                                const std::vector<FitResult>& fits, const Record& record,
                                const DavarOptions& davar, OutputFormat format) {
  std::vector<std::vector<ReportedParameter>> rows;
  for (const auto& fit : fits) rows.push_back(reported_parameters(fit));
  const auto& columns = rows.front();
  if (format == OutputFormat::kJson) {
    nlohmann::json out = {{"units", unit_name(record.unit)}, {"window", davar.window},
                          {"step", davar.step}, {"t", time_s}, {"terms", nlohmann::json::array()}};
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c == 0 || columns[c].term != columns[c - 1].term) {
        out["terms"].push_back({{"type", columns[c].term}});
      }
      auto& term = out["terms"].back();
      term[columns[c].name] = nlohmann::json::array();
      term[columns[c].name + "_sigma"] = nlohmann::json::array();
      for (const auto& row : rows) {
        term[columns[c].name].push_back(row[c].value);
        term[columns[c].name + "_sigma"].push_back(std::isfinite(row[c].sigma)
                                                       ? nlohmann::json(row[c].sigma)
                                                       : nlohmann::json());
      }
    }
    // Added beside the series (issue #26): whether each window's fit failed, and why.
    out["failed"] = nlohmann::json::array();
    out["failure"] = nlohmann::json::array();
    for (const auto& fit : fits) {
      out["failed"].push_back(fit.diagnostics.failed());
      out["failure"].push_back(fit.diagnostics.failure());
    }
    return out.dump(1) + "\n";
  }
  const bool csv = format == OutputFormat::kCsv;
  std::string out = csv ? "t" : fmt::format("# windowed fit: window {} step {} samples\n#{:>11}",
                                            davar.window, davar.step, "t_s");
  for (const auto& c : columns) {
    const std::string name = c.name + "[" + c.unit + "]";
    out += csv ? fmt::format(",{},{}_sigma", c.name, c.name)
               : fmt::format(" {:>22} {:>10}", name, "sigma");
  }
  out += csv ? ",failed\n" : "\n";
  for (std::size_t k = 0; k < rows.size(); ++k) {
    out += csv ? fmt::format("{:.10g}", time_s[k]) : fmt::format("{:>12.6g}", time_s[k]);
    for (const auto& p : rows[k]) {
      out += csv ? fmt::format(",{:.6g},{:.3g}", p.value, p.sigma)
                 : fmt::format(" {:>22.5g} {:>10.3g}", p.value, p.sigma);
    }
    out += csv ? fmt::format(",{}\n", fits[k].diagnostics.failed() ? 1 : 0) : "\n";
  }
  if (!csv) {
    for (std::size_t k = 0; k < fits.size(); ++k) {
      if (fits[k].diagnostics.failed()) {
        out += fmt::format("# FIT FAILED at t = {:g} s: {}\n", time_s[k],
                           fits[k].diagnostics.failure());
      }
    }
  }
  return out;
}

}  // namespace stochnav::cli

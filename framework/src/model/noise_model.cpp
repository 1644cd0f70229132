#include "stochnav/model/noise_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

bool close(double a, double b, double rel_tol) {
  if (a == b) return true;
  return std::abs(a - b) <= rel_tol * std::max(std::abs(a), std::abs(b));
}

std::string range_text(ParameterRange range) {
  switch (range) {
    case ParameterRange::kNonNegative:
      return "a number >= 0";
    case ParameterRange::kPositive:
      return "a number > 0";
    case ParameterRange::kAny:
      return "a finite number";
  }
  return "a number";
}

std::optional<ModelIssue> find_segment_issue(const NonstationaryTerm& term,
                                             const std::string& pointer) {
  if (term.segments.empty()) {
    return ModelIssue{pointer + "/segments", "no segments",
                      "at least one {\"start\": s, \"end\": s, \"scale\": x} segment"};
  }
  double previous_end = 0.0;
  for (std::size_t k = 0; k < term.segments.size(); ++k) {
    const auto& segment = term.segments[k];
    const std::string at = fmt::format("{}/segments/{}", pointer, k);
    if (!std::isfinite(segment.start_s) || segment.start_s < 0.0) {
      return ModelIssue{at + "/start", fmt::format("{} is invalid", segment.start_s),
                        "a record time in s >= 0"};
    }
    if (!std::isfinite(segment.end_s) || !(segment.end_s > segment.start_s)) {
      return ModelIssue{at + "/end", fmt::format("{} is not after start {}", segment.end_s,
                                                 segment.start_s),
                        "a record time in s > start"};
    }
    if (!std::isfinite(segment.scale) || segment.scale < 0.0) {
      return ModelIssue{at + "/scale", fmt::format("{} is invalid", segment.scale),
                        "a factor >= 0"};
    }
    if (k > 0 && segment.start_s < previous_end) {
      return ModelIssue{at + "/start",
                        fmt::format("{} overlaps or precedes the previous segment ending at {}",
                                    segment.start_s, previous_end),
                        "segments in ascending time order without overlap"};
    }
    previous_end = segment.end_s;
  }
  return std::nullopt;
}

}  // namespace

std::optional<ModelIssue> find_model_issue(const NoiseModel& model) {
  if (!std::isfinite(model.rate_hz) || !(model.rate_hz > 0.0)) {
    return ModelIssue{"/rate_hz", fmt::format("{} is not a valid rate", model.rate_hz),
                      "a sampling rate in Hz > 0"};
  }
  const Quantity quantity = quantity_of(model.unit);
  bool seen_nonstationary = false;
  for (std::size_t i = 0; i < model.terms.size(); ++i) {
    const NoiseTerm& term = model.terms[i];
    const std::string pointer = fmt::format("/terms/{}", i);
    if (const auto* nonstationary = std::get_if<NonstationaryTerm>(&term)) {
      if (seen_nonstationary) {
        return ModelIssue{pointer, "is a second nonstationary term",
                          "at most one nonstationary term holding all segments"};
      }
      seen_nonstationary = true;
      if (auto issue = find_segment_issue(*nonstationary, pointer)) return issue;
      continue;
    }
    const auto specs = parameter_specs(term_type(term));
    for (std::size_t j = 0; j < specs.size(); ++j) {
      const auto value = parameter_value(term, j);
      if (!value) {
        if (specs[j].optional) continue;
        return ModelIssue{pointer + "/" + std::string(specs[j].name), "is missing",
                          range_text(specs[j].range)};
      }
      const double reported = to_reported(quantity, specs[j].dimension, *value);
      const bool ok = std::isfinite(*value) &&
                      (specs[j].range == ParameterRange::kAny ||
                       (specs[j].range == ParameterRange::kNonNegative && *value >= 0.0) ||
                       (specs[j].range == ParameterRange::kPositive && *value > 0.0));
      if (!ok) {
        return ModelIssue{pointer + "/" + std::string(specs[j].name),
                          fmt::format("{} is out of range", reported),
                          fmt::format("{} in {}", range_text(specs[j].range),
                                      reported_unit_name(quantity, specs[j].dimension))};
      }
    }
  }
  return std::nullopt;
}

bool equals(const NoiseTerm& a, const NoiseTerm& b, double rel_tol) {
  if (a.index() != b.index()) return false;
  if (const auto* na = std::get_if<NonstationaryTerm>(&a)) {
    const auto& nb = std::get<NonstationaryTerm>(b);
    if (na->segments.size() != nb.segments.size()) return false;
    for (std::size_t k = 0; k < na->segments.size(); ++k) {
      const auto& sa = na->segments[k];
      const auto& sb = nb.segments[k];
      if (!close(sa.start_s, sb.start_s, rel_tol) || !close(sa.end_s, sb.end_s, rel_tol) ||
          !close(sa.scale, sb.scale, rel_tol)) {
        return false;
      }
    }
    return true;
  }
  if (const auto* aa = std::get_if<AuxSensitivityTerm>(&a)) {
    if (aa->column != std::get<AuxSensitivityTerm>(b).column) return false;
  }
  const auto specs = parameter_specs(term_type(a));
  for (std::size_t j = 0; j < specs.size(); ++j) {
    const auto va = parameter_value(a, j);
    const auto vb = parameter_value(b, j);
    if (va.has_value() != vb.has_value()) return false;
    if (va && !close(*va, *vb, rel_tol)) return false;
  }
  return true;
}

bool equals(const NoiseModel& a, const NoiseModel& b, double rel_tol) {
  if (a.unit != b.unit || !close(a.rate_hz, b.rate_hz, rel_tol)) return false;
  if (a.terms.size() != b.terms.size()) return false;
  for (std::size_t i = 0; i < a.terms.size(); ++i) {
    if (!equals(a.terms[i], b.terms[i], rel_tol)) return false;
  }
  return true;
}

std::string describe(const NoiseTerm& term, Quantity quantity, const NoiseTerm* sigma_natural) {
  const TermType type = term_type(term);
  std::string text(term_type_name(type));
  text += ":";
  if (const auto* nonstationary = std::get_if<NonstationaryTerm>(&term)) {
    for (std::size_t k = 0; k < nonstationary->segments.size(); ++k) {
      const auto& s = nonstationary->segments[k];
      text += fmt::format("{} x{:.6g} over [{:.6g}, {:.6g}) s", k == 0 ? "" : ",", s.scale,
                          s.start_s, s.end_s);
    }
    return text;
  }
  const auto specs = parameter_specs(type);
  bool first = true;
  if (const auto* aux = std::get_if<AuxSensitivityTerm>(&term)) {
    text += fmt::format(" column {},", aux->column);
  }
  for (std::size_t j = 0; j < specs.size(); ++j) {
    const auto value = parameter_value(term, j);
    if (!value) continue;
    text += fmt::format("{} {} = {:.6g}", first ? "" : ",", specs[j].name,
                        to_reported(quantity, specs[j].dimension, *value));
    first = false;
    if (sigma_natural != nullptr && sigma_natural->index() == term.index()) {
      const auto sigma = parameter_value(*sigma_natural, j);
      if (sigma) {
        text += fmt::format(" +/- {:.2g}", to_reported(quantity, specs[j].dimension, *sigma));
      }
    }
    text += fmt::format(" {}", reported_unit_name(quantity, specs[j].dimension));
  }
  return text;
}

std::string describe(const NoiseModel& model) {
  std::string text = fmt::format("noise model: {} at {:.6g} Hz, {} term{}", unit_name(model.unit),
                                 model.rate_hz, model.terms.size(),
                                 model.terms.size() == 1 ? "" : "s");
  for (const auto& term : model.terms) {
    text += fmt::format("\n  {}", describe(term, quantity_of(model.unit)));
  }
  return text;
}

}  // namespace stochnav

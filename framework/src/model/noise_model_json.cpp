#include "stochnav/model/noise_model_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/nearest_name.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

using nlohmann::json;

constexpr std::string_view kUnitChoices = "one of \"deg/h\", \"deg/s\", \"rad/s\", \"m/s^2\", "
                                          "\"g\", \"plain\"";

// Escapes a key as a JSON pointer reference token (RFC 6901).
std::string pointer_token(std::string_view key) {
  std::string token;
  for (char c : key) {
    if (c == '~') {
      token += "~0";
    } else if (c == '/') {
      token += "~1";
    } else {
      token += c;
    }
  }
  return token;
}

[[noreturn]] void fail(const std::string& pointer, const std::string& problem,
                       std::string_view expected) {
  throw ConfigError(fmt::format("{}: {}; expected {}", pointer.empty() ? "(root)" : pointer,
                                problem, expected));
}

std::string type_problem(const json& value, std::string_view wanted) {
  return fmt::format("is {} {}, not {}", value.is_array() || value.is_object() ? "an" : "a",
                     value.type_name(), wanted);
}

const json& require_object(const json& value, const std::string& pointer,
                           std::string_view expected) {
  if (!value.is_object()) fail(pointer, type_problem(value, "an object"), expected);
  return value;
}

double require_number(const json& value, const std::string& pointer, std::string_view expected) {
  if (!value.is_number()) fail(pointer, type_problem(value, "a number"), expected);
  const double number = value.get<double>();
  if (!std::isfinite(number)) fail(pointer, "is not finite", expected);
  return number;
}

const json& require_key(const json& object, std::string_view key, const std::string& pointer,
                        std::string_view expected) {
  const auto it = object.find(key);
  if (it == object.end()) fail(pointer + "/" + pointer_token(key), "is missing", expected);
  return *it;
}

std::string term_form(TermType type, Quantity quantity) {
  std::string form = fmt::format("{{\"type\": \"{}\"", term_type_name(type));
  if (type == TermType::kNonstationary) {
    return form + ", \"segments\": [{\"start\": s, \"end\": s, \"scale\": x}, ...]}";
  }
  if (type == TermType::kAuxSensitivity) form += ", \"column\": \"temperature_c\"";
  for (const auto& spec : parameter_specs(type)) {
    form += fmt::format(", \"{}\": {}{}", spec.name,
                        reported_unit_name(quantity, spec.dimension),
                        spec.optional ? " (optional)" : "");
  }
  return form + "}";
}

NonstationaryTerm parse_nonstationary(const json& object, const std::string& pointer,
                                      std::string_view form) {
  for (const auto& [key, value] : object.items()) {
    if (key != "type" && key != "segments") {
      fail(pointer + "/" + pointer_token(key), "is an unknown key", form);
    }
  }
  const std::string segments_pointer = pointer + "/segments";
  const json& segments = require_key(object, "segments", pointer, form);
  if (!segments.is_array()) fail(segments_pointer, type_problem(segments, "an array"), form);
  constexpr std::string_view kSegmentForm =
      "{\"start\": s, \"end\": s, \"scale\": x} with record times in s";
  NonstationaryTerm term;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const std::string at = fmt::format("{}/{}", segments_pointer, k);
    const json& segment = require_object(segments[k], at, kSegmentForm);
    for (const auto& [key, value] : segment.items()) {
      if (key != "start" && key != "end" && key != "scale") {
        fail(at + "/" + pointer_token(key), "is an unknown key", kSegmentForm);
      }
    }
    NonstationarySegment parsed;
    parsed.start_s = require_number(require_key(segment, "start", at, "a record time in s >= 0"),
                                    at + "/start", "a record time in s >= 0");
    parsed.end_s = require_number(require_key(segment, "end", at, "a record time in s > start"),
                                  at + "/end", "a record time in s > start");
    parsed.scale = require_number(require_key(segment, "scale", at, "a factor >= 0"),
                                  at + "/scale", "a factor >= 0");
    term.segments.push_back(parsed);
  }
  return term;
}

// Range checks of one term through the model rules, so they live in one place.
void check_term_ranges(const NoiseTerm& term, Unit unit, const std::string& pointer) {
  NoiseModel single{unit, 1.0, {term}};
  if (auto issue = find_model_issue(single)) {
    // issue->pointer starts with "/terms/0".
    constexpr std::string_view kLocal = "/terms/0";
    fail(pointer + issue->pointer.substr(kLocal.size()), issue->problem, issue->expected);
  }
}

double tidy(double value) {
  // 15 significant digits: 0.05 written as 0.05 after a round trip through natural units.
  // strtod, not stod: stod throws out_of_range for a subnormal (1e-320), which is a number.
  const std::string text = fmt::format("{:.15g}", value);
  return std::strtod(text.c_str(), nullptr);
}

}  // namespace

NoiseTerm noise_term_from_json(const json& value, Unit unit, std::string_view pointer_view) {
  const std::string pointer(pointer_view);
  const Quantity quantity = quantity_of(unit);
  const json& object = require_object(
      value, pointer, "a term object {\"type\": \"angle_random_walk\", \"N\": ...}");
  const json& type_value = require_key(object, "type", pointer, "a term type such as \"quantization\"");
  if (!type_value.is_string()) {
    fail(pointer + "/type", type_problem(type_value, "a string"),
         "a term type such as \"quantization\"");
  }
  const std::string type_name = type_value.get<std::string>();
  const auto type = parse_term_type(type_name);
  if (!type) {
    std::string choices;
    for (TermType t : all_term_types()) {
      choices += (choices.empty() ? "" : ", ") + std::string(term_type_name(t));
    }
    fail(pointer + "/type", fmt::format("unknown term type \"{}\"", type_name),
         "one of " + choices);
  }
  const std::string form = term_form(*type, quantity);
  if (*type == TermType::kNonstationary) {
    NoiseTerm term = parse_nonstationary(object, pointer, form);
    check_term_ranges(term, unit, pointer);
    return term;
  }

  NoiseTerm term = make_term(*type);
  const auto specs = parameter_specs(*type);
  for (const auto& [key, entry] : object.items()) {
    if (key == "type") continue;
    if (key == "column" && *type == TermType::kAuxSensitivity) {
      const std::string at = pointer + "/column";
      if (!entry.is_string() || entry.get<std::string>().empty()) {
        fail(at, type_problem(entry, "a non-empty string"),
             "the CSV column of the auxiliary channel, e.g. \"temperature_c\"");
      }
      std::get<AuxSensitivityTerm>(term).column = entry.get<std::string>();
      continue;
    }
    const std::string at = pointer + "/" + pointer_token(key);
    bool known = false;
    for (const auto& spec : specs) {
      if (key == spec.name) {
        known = true;
      } else if (key == std::string(spec.name) + "_sigma") {
        known = true;
        if (!entry.is_null()) {
          const std::string expected = fmt::format(
              "a 1-sigma uncertainty >= 0 in {} or null",
              reported_unit_name(quantity, spec.dimension));
          if (require_number(entry, at, expected) < 0.0) fail(at, "is negative", expected);
        }
      }
    }
    if (!known) {
      std::vector<std::string> names = {"type"};
      for (const auto& spec : specs) names.emplace_back(spec.name);
      if (const auto nearest = nearest_name(key, names)) {
        fail(at, "is an unknown key (did you mean '" + *nearest + "'?)", form);
      }
      fail(at, "is an unknown key", form);
    }
  }
  for (std::size_t j = 0; j < specs.size(); ++j) {
    const std::string key(specs[j].name);
    const std::string expected =
        fmt::format("a number in {}", reported_unit_name(quantity, specs[j].dimension));
    const auto it = object.find(key);
    if (it == object.end()) {
      if (specs[j].optional) continue;
      fail(pointer + "/" + key, "is missing", expected + " (term form " + form + ")");
    }
    const double reported = require_number(*it, pointer + "/" + key, expected);
    set_parameter_value(term, j, to_natural(quantity, specs[j].dimension, reported));
  }
  check_term_ranges(term, unit, pointer);
  return term;
}

NoiseModel noise_model_from_json(const json& value, std::string_view pointer_prefix) {
  const std::string root(pointer_prefix);
  constexpr std::string_view kModelForm =
      "a noise model {\"units\": \"deg/h\", \"rate_hz\": 100, \"terms\": [...]}";
  const json& object = require_object(value, root, kModelForm);
  for (const auto& [key, entry] : object.items()) {
    if (key == "units" || key == "rate_hz" || key == "terms") continue;
    if (key == "diagnostics") {
      require_object(entry, root + "/diagnostics", "the diagnostics object of a fit result");
      continue;
    }
    // What `stochnav fit` writes beside the model: how it was fitted, and the GMWM ranking.
    if (key == "method") {
      if (!entry.is_string()) {
        fail(root + "/method", type_problem(entry, "a string"), "a fit's method, avar or gmwm");
      }
      continue;
    }
    if (key == "ranking") {
      if (!entry.is_array()) {
        fail(root + "/ranking", type_problem(entry, "an array"), "a GMWM fit's model ranking");
      }
      continue;
    }
    fail(root + "/" + pointer_token(key), "is an unknown key",
         "only \"units\", \"rate_hz\", \"terms\" (and \"method\", \"diagnostics\", "
         "\"ranking\" from a fit)");
  }

  NoiseModel model;
  const json& units = require_key(object, "units", root, kUnitChoices);
  if (!units.is_string()) fail(root + "/units", type_problem(units, "a string"), kUnitChoices);
  try {
    model.unit = parse_unit(units.get<std::string>());
  } catch (const ConfigError&) {
    fail(root + "/units", fmt::format("unknown unit \"{}\"", units.get<std::string>()),
         kUnitChoices);
  }
  constexpr std::string_view kRateForm = "the sampling rate in Hz, a number > 0";
  model.rate_hz = require_number(require_key(object, "rate_hz", root, kRateForm),
                                 root + "/rate_hz", kRateForm);
  if (!(model.rate_hz > 0.0)) {
    fail(root + "/rate_hz", fmt::format("{} is not positive", model.rate_hz), kRateForm);
  }

  constexpr std::string_view kTermsForm = "an array of term objects";
  const json& terms = require_key(object, "terms", root, kTermsForm);
  if (!terms.is_array()) fail(root + "/terms", type_problem(terms, "an array"), kTermsForm);
  for (std::size_t i = 0; i < terms.size(); ++i) {
    model.terms.push_back(
        noise_term_from_json(terms[i], model.unit, fmt::format("{}/terms/{}", root, i)));
  }
  if (auto issue = find_model_issue(model)) {
    fail(root + issue->pointer, issue->problem, issue->expected);
  }
  return model;
}

json to_json(const NoiseTerm& term, Unit unit) {
  const Quantity quantity = quantity_of(unit);
  const TermType type = term_type(term);
  json out = json::object();
  out["type"] = std::string(term_type_name(type));
  if (const auto* nonstationary = std::get_if<NonstationaryTerm>(&term)) {
    json segments = json::array();
    for (const auto& s : nonstationary->segments) {
      segments.push_back({{"start", tidy(s.start_s)}, {"end", tidy(s.end_s)},
                          {"scale", tidy(s.scale)}});
    }
    out["segments"] = std::move(segments);
    return out;
  }
  if (const auto* aux = std::get_if<AuxSensitivityTerm>(&term)) out["column"] = aux->column;
  const auto specs = parameter_specs(type);
  for (std::size_t j = 0; j < specs.size(); ++j) {
    const auto value = parameter_value(term, j);
    if (!value) continue;
    out[std::string(specs[j].name)] = tidy(to_reported(quantity, specs[j].dimension, *value));
  }
  return out;
}

json to_json(const NoiseModel& model) {
  json terms = json::array();
  for (const auto& term : model.terms) terms.push_back(to_json(term, model.unit));
  return {{"units", unit_name(model.unit)}, {"rate_hz", tidy(model.rate_hz)},
          {"terms", std::move(terms)}};
}

}  // namespace stochnav

#include "stochnav/fit/parameter_control_names.hpp"

#include <fmt/format.h>

#include <map>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_option_names.hpp"
#include "stochnav/io/text_cells.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

enum class ControlKind { kStart, kFix, kBound };

std::string_view option_name(ControlKind kind) {
  switch (kind) {
    case ControlKind::kStart:
      return "--start";
    case ControlKind::kFix:
      return "--fix";
    default:
      return "--bound";
  }
}

double parse_value(std::string_view text, std::string_view option, std::string_view item) {
  double value = 0.0;
  if (!parse_number(text, value) || !std::isfinite(value)) {
    throw ConfigError(fmt::format("{} '{}': '{}' is not a number", option, item, text));
  }
  return value;
}

class ControlParser {
 public:
  ControlParser(std::span<const TermType> terms, Unit unit)
      : terms_(terms), quantity_(quantity_of(unit)) {}

  void add(ControlKind kind, std::string_view list) {
    std::map<std::string, std::size_t> mentions;  // TERM.PARAM -> times named so far
    const std::string_view option = option_name(kind);
    for (const std::string& item : split_comma_list(list)) {
      if (trim(item).empty()) continue;
      const auto dot = item.find('.');
      const auto equals = item.find('=');
      if (dot == std::string::npos || equals == std::string::npos || equals < dot) {
        throw ConfigError(
            fmt::format("{} '{}': write TERM.PARAM={} (e.g. "
                        "gauss_markov.tau_c={})",
                        option, item, kind == ControlKind::kBound ? "LOW:HIGH" : "VALUE",
                        kind == ControlKind::kBound ? "1:100" : "20"));
      }
      std::string term_name(trim(std::string_view(item).substr(0, dot)));
      const std::string parameter(trim(std::string_view(item).substr(dot + 1, equals - dot - 1)));
      const std::string_view value_text = std::string_view(item).substr(equals + 1);
      std::size_t occurrence = 0;
      if (const auto hash = term_name.find('#'); hash != std::string::npos) {
        occurrence =
            static_cast<std::size_t>(parse_value(term_name.substr(hash + 1), option, item));
        term_name.resize(hash);
        if (occurrence < 1)
          throw ConfigError(fmt::format("{} '{}': #K counts from 1", option, item));
        --occurrence;
      } else {
        occurrence = mentions[term_name + "." + parameter]++;
      }
      ParameterControl& control = control_for(term_name, occurrence, parameter, option, item);
      const ParameterSpec& spec = parameter_specs(terms_[control.term])[control.parameter];
      auto natural = [&](std::string_view text) {
        return to_natural(quantity_, spec.dimension, parse_value(text, option, item));
      };
      if (kind == ControlKind::kBound) {
        const auto colon = value_text.find(':');
        if (colon == std::string_view::npos) {
          throw ConfigError(fmt::format("{} '{}': give LOW:HIGH", option, item));
        }
        control.lower = natural(value_text.substr(0, colon));
        control.upper = natural(value_text.substr(colon + 1));
      } else {
        (kind == ControlKind::kFix ? control.fixed : control.start) = natural(value_text);
      }
    }
  }

  std::vector<ParameterControl> controls() const {
    std::vector<ParameterControl> out;
    for (const auto& [key, control] : controls_) out.push_back(control);
    return out;
  }

 private:
  ParameterControl& control_for(const std::string& term_name, std::size_t occurrence,
                                const std::string& parameter, std::string_view option,
                                std::string_view item) {
    const auto type = parse_term_type(term_name);
    std::size_t seen = 0;
    for (std::size_t t = 0; t < terms_.size(); ++t) {
      if (!type || terms_[t] != *type || seen++ != occurrence) continue;
      const auto specs = parameter_specs(*type);
      for (std::size_t p = 0; p < specs.size(); ++p) {
        if (specs[p].name != parameter) continue;
        auto& control = controls_[{t, p}];
        control.term = t;
        control.parameter = p;
        return control;
      }
      std::string names;
      for (const auto& spec : specs) names += (names.empty() ? "" : ", ") + std::string(spec.name);
      throw ConfigError(fmt::format("{} '{}': {} has no parameter '{}'; it has {}", option, item,
                                    term_name, parameter, names));
    }
    throw ConfigError(
        fmt::format("{} '{}': the model has {} {} term(s); name a term of --terms "
                    "(TERM#K picks the K-th of a repeated one)",
                    option, item, seen, term_name));
  }

  std::span<const TermType> terms_;
  Quantity quantity_;
  std::map<std::pair<std::size_t, std::size_t>, ParameterControl> controls_;
};

}  // namespace

std::vector<ParameterControl> parse_parameter_controls(std::span<const TermType> terms, Unit unit,
                                                       std::string_view start, std::string_view fix,
                                                       std::string_view bound) {
  ControlParser parser(terms, unit);
  parser.add(ControlKind::kStart, start);
  parser.add(ControlKind::kFix, fix);
  parser.add(ControlKind::kBound, bound);
  return parser.controls();
}

}  // namespace stochnav

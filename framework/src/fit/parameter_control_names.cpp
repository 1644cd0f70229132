#include "stochnav/fit/parameter_control_names.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_option_names.hpp"
#include "stochnav/io/text_cells.hpp"
#include "stochnav/model/reporting_units.hpp"

namespace stochnav {
namespace {

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

double parse_value(std::string_view text, std::string_view where) {
  double value = 0.0;
  if (!parse_number(text, value) || !std::isfinite(value)) {
    throw ConfigError(fmt::format("{}: '{}' is not a number", where, text));
  }
  return value;
}

class ControlMerger {
 public:
  ControlMerger(std::span<const TermType> terms, Quantity quantity)
      : terms_(terms), quantity_(quantity) {}

  void add(const ControlItem& item, std::size_t mention) {
    const auto dot = item.name.find('.');
    if (dot == std::string::npos) {
      throw ConfigError(
          fmt::format("{}: name the parameter as TERM.PARAM (e.g. "
                      "gauss_markov.tau_c)",
                      item.where));
    }
    std::string term_name(trim(std::string_view(item.name).substr(0, dot)));
    const std::string parameter(trim(std::string_view(item.name).substr(dot + 1)));
    std::size_t occurrence = mention;
    if (const auto hash = term_name.find('#'); hash != std::string::npos) {
      const double k = parse_value(term_name.substr(hash + 1), item.where);
      if (k < 1.0 || k != std::floor(k)) {
        throw ConfigError(fmt::format("{}: #K counts terms from 1", item.where));
      }
      occurrence = static_cast<std::size_t>(k) - 1;
      term_name.resize(hash);
    }
    ParameterControl& control = control_for(term_name, occurrence, parameter, item.where);
    const ParameterSpec& spec = parameter_specs(terms_[control.term])[control.parameter];
    std::vector<double> natural;
    for (double value : item.values) {
      natural.push_back(to_natural(quantity_, spec.dimension, value));
    }
    if (item.kind == ControlKind::kBound) {
      control.lower = natural.at(0);
      control.upper = natural.at(1);
    } else {
      (item.kind == ControlKind::kFix ? control.fixed : control.start) = natural.at(0);
    }
  }

  std::vector<ParameterControl> controls() const {
    std::vector<ParameterControl> out;
    for (const auto& [key, control] : controls_) out.push_back(control);
    return out;
  }

 private:
  ParameterControl& control_for(const std::string& term_name, std::size_t occurrence,
                                const std::string& parameter, std::string_view where) {
    const auto type = parse_term_type(term_name);
    if (!type) {
      throw ConfigError(
          fmt::format("{}: unknown term '{}'; name a term of the model's terms", where, term_name));
    }
    std::size_t seen = 0;
    for (std::size_t t = 0; t < terms_.size(); ++t) {
      if (terms_[t] != *type || seen++ != occurrence) continue;
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
      throw ConfigError(fmt::format("{}: {} has no parameter '{}'; it has {}", where, term_name,
                                    parameter, names));
    }
    throw ConfigError(
        fmt::format("{}: the model has {} {} term(s); name a term of the model's terms "
                    "(TERM#K picks the K-th of a repeated one)",
                    where, seen, term_name));
  }

  std::span<const TermType> terms_;
  Quantity quantity_;
  std::map<std::pair<std::size_t, std::size_t>, ParameterControl> controls_;
};

// The items of one option's comma-separated text.
void add_option_items(ControlKind kind, std::string_view list, std::vector<ControlItem>& items) {
  const std::string_view option = option_name(kind);
  const bool bound = kind == ControlKind::kBound;
  for (const std::string& text : split_comma_list(list)) {
    if (trim(text).empty()) continue;
    const std::string where = fmt::format("{} '{}'", option, text);
    const auto dot = text.find('.');
    const auto equals = text.find('=');
    if (dot == std::string::npos || equals == std::string::npos || equals < dot) {
      throw ConfigError(fmt::format("{}: write TERM.PARAM={} (e.g. gauss_markov.tau_c={})", where,
                                    bound ? "LOW:HIGH" : "VALUE", bound ? "1:100" : "20"));
    }
    const std::string_view value_text = std::string_view(text).substr(equals + 1);
    ControlItem item{kind, text.substr(0, equals), {}, where};
    if (bound) {
      const auto colon = value_text.find(':');
      if (colon == std::string_view::npos) {
        throw ConfigError(fmt::format("{}: give LOW:HIGH", where));
      }
      item.values = {parse_value(value_text.substr(0, colon), where),
                     parse_value(value_text.substr(colon + 1), where)};
    } else {
      item.values = {parse_value(value_text, where)};
    }
    items.push_back(std::move(item));
  }
}

}  // namespace

std::vector<ParameterControl> control_items_to_controls(std::span<const TermType> terms,
                                                        Quantity quantity,
                                                        std::span<const ControlItem> items) {
  ControlMerger merger(terms, quantity);
  std::map<std::pair<ControlKind, std::string>, std::size_t> mentions;  // times named so far
  for (const ControlItem& item : items) {
    std::string name = item.name;
    std::erase_if(name, [](char c) { return c == ' ' || c == '\t'; });
    merger.add(item, mentions[{item.kind, name}]++);
  }
  return merger.controls();
}

std::vector<ParameterControl> parse_parameter_controls(std::span<const TermType> terms, Unit unit,
                                                       std::string_view start, std::string_view fix,
                                                       std::string_view bound) {
  std::vector<ControlItem> items;
  add_option_items(ControlKind::kStart, start, items);
  add_option_items(ControlKind::kFix, fix, items);
  add_option_items(ControlKind::kBound, bound, items);
  std::vector<ParameterControl> controls =
      control_items_to_controls(terms, quantity_of(unit), items);
  if (const auto issue = check_parameter_controls(terms, controls)) {
    throw ConfigError("--" + issue->message());
  }
  return controls;
}

}  // namespace stochnav

#include "stochnav/plugin/fit_steering.hpp"

#include <fmt/format.h>

#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav::plugin {
namespace {

/// "~" and "/" escaped as a JSON pointer token (RFC 6901).
std::string pointer_token(std::string_view name) {
  std::string token;
  for (char c : name) token += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return token;
}

ValueCodec<std::vector<ControlItem>> steering_codec(ControlKind kind, std::string_view key) {
  const bool bound = kind == ControlKind::kBound;
  const std::string expected =
      bound ? "[LOW, HIGH], two numbers > 0 in reporting units" : "a number > 0 in reporting units";
  ValueCodec<std::vector<ControlItem>> codec;
  codec.read = [kind, key, bound, expected](ParamReader& reader, Quantity) {
    std::vector<ControlItem> items;
    if (!reader.has(key)) return items;
    const nlohmann::json& object = reader.raw(key);
    const std::string pointer = reader.pointer(key);
    if (!object.is_object()) {
      param_table_detail::reject(
          pointer, object,
          "an object {\"TERM[#K].PARAM\": " + std::string(bound ? "[LOW, HIGH]" : "VALUE") + "}");
    }
    for (const auto& [name, value] : object.items()) {
      const std::string where = pointer + "/" + pointer_token(name);
      const bool shape = bound ? value.is_array() && value.size() == 2 : value.is_number();
      ControlItem item{kind, name, {}, where};
      if (shape) {
        for (const auto& number : bound ? value : nlohmann::json::array({value})) {
          if (!number.is_number() || !(number.get<double>() > 0.0) ||
              !std::isfinite(number.get<double>())) {
            item.values.clear();
            break;
          }
          item.values.push_back(number.get<double>());
        }
      }
      if (item.values.empty()) param_table_detail::reject(where, value, expected);
      items.push_back(std::move(item));
    }
    return items;
  };
  codec.write = [bound](const std::vector<ControlItem>& items, Quantity) {
    nlohmann::json object = nlohmann::json::object();
    for (const ControlItem& item : items) {
      object[item.name] = bound ? nlohmann::json(item.values) : nlohmann::json(item.values.at(0));
    }
    return object;
  };
  codec.describe = [codec_write = codec.write](const std::vector<ControlItem>& items, Quantity q) {
    return codec_write(items, q).dump();
  };
  codec.equal = [](const std::vector<ControlItem>& a, const std::vector<ControlItem>& b, double) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].name != b[i].name || a[i].values != b[i].values) return false;
    }
    return true;
  };
  codec.form = bound ? "an object {\"TERM[#K].PARAM\": [LOW, HIGH]} in reporting units, default {}"
                     : "an object {\"TERM[#K].PARAM\": VALUE} in reporting units, default {}";
  return codec;
}

}  // namespace

std::string FitSteering::issue_pointer(const ParameterControlIssue& issue) const {
  const auto parent = [](const std::string& pointer) {
    return pointer.substr(0, pointer.rfind('/'));
  };
  const auto& items = issue.key == "start" ? start : issue.key == "fix" ? fix : bound;
  for (const ControlItem& item : items) {
    if (item.name == issue.label) return item.where;
  }
  if (!items.empty()) return parent(items.front().where);
  const ControlItem& any = !start.empty() ? start.front()
                           : !fix.empty() ? fix.front()
                                          : bound.front();
  return parent(parent(any.where)) + "/" + issue.key;
}

std::vector<ParameterControl> FitSteering::controls(std::span<const TermType> terms,
                                                    SensorGroup group) const {
  if (empty()) return {};
  std::vector<ControlItem> items = start;
  items.insert(items.end(), fix.begin(), fix.end());
  items.insert(items.end(), bound.begin(), bound.end());
  std::vector<ParameterControl> result =
      control_items_to_controls(terms, sensor_quantity(group), items);
  if (const auto issue = check_parameter_controls(terms, result)) {
    throw ConfigError(fmt::format("{}: {}", issue_pointer(*issue), issue->reason));
  }
  return result;
}

const ParamTable<FitSteering>& fit_steering_table() {
  static const ParamTable<FitSteering> table{
      custom(&FitSteering::start, "start", steering_codec(ControlKind::kStart, "start"),
             "starting values of the fitted parameters (TERM[#K].PARAM as stochnav fit --start)"),
      custom(&FitSteering::fix, "fix", steering_codec(ControlKind::kFix, "fix"),
             "parameters held at a value, reported with sigma 0 (as stochnav fit --fix)"),
      custom(&FitSteering::bound, "bound", steering_codec(ControlKind::kBound, "bound"),
             "search ranges of fitted parameters (as stochnav fit --bound)")};
  return table;
}

const ParamTable<TermFitOptions>& term_fit_table() {
  static const ParamTable<TermFitOptions> table =
      ParamTable<TermFitOptions>{
          choice(&TermFitOptions::method, "method",
                 {{"avar", CalibrationEstimator::kAllanVariance},
                  {"gmwm", CalibrationEstimator::kGmwm}},
                 CalibrationEstimator::kAllanVariance,
                 "estimator: the Allan variance or GMWM (the wavelet variance; not with an "
                 "automatic term selection)")}
          .plus(lift(&TermFitOptions::steering, fit_steering_table()));
  return table;
}

}  // namespace stochnav::plugin

#include "stochnav/plugin/params.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/nearest_name.hpp"

namespace stochnav::plugin {
namespace {

std::string escape_pointer_token(std::string_view key) {
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

std::string bound_text_of(Bound bound, std::string_view unit) {
  std::string text;
  switch (bound) {
    case Bound::kAny:
      text = "a finite number";
      break;
    case Bound::kNonNegative:
      text = "a number >= 0";
      break;
    case Bound::kPositive:
      text = "a number > 0";
      break;
    case Bound::kOpenUnit:
      text = "a number in (0, 1)";
      break;
  }
  if (!unit.empty()) text += " (" + std::string(unit) + ")";
  return text;
}

}  // namespace

bool within_bound(Bound bound, double value) {
  if (!std::isfinite(value)) return false;
  switch (bound) {
    case Bound::kAny:
      return true;
    case Bound::kNonNegative:
      return value >= 0.0;
    case Bound::kPositive:
      return value > 0.0;
    case Bound::kOpenUnit:
      return value > 0.0 && value < 1.0;
  }
  return false;
}

namespace {

std::string shown(const nlohmann::json& value) {
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

}  // namespace

std::string bound_description(Bound bound, std::string_view unit) {
  return bound_text_of(bound, unit);
}

namespace {
std::string bound_text(Bound bound, std::string_view unit) { return bound_text_of(bound, unit); }
}  // namespace

ParamReader::ParamReader(const nlohmann::json& params, std::string pointer)
    : params_(params), pointer_(std::move(pointer)) {
  if (!params_.is_object() && !params_.is_null()) {
    throw ConfigError((pointer_.empty() ? std::string("/") : pointer_) + ": found " +
                      shown(params_) + "; expected an object of parameters");
  }
}

void ParamReader::expect(std::string_view key) { expected_.emplace(key); }

void ParamReader::throw_missing(std::string_view key, const std::string& expected) const {
  if (params_.is_object()) {
    for (const auto& [name, value] : params_.items()) {
      if (known_.count(name) != 0 || expected_.count(name) != 0) continue;
      if (likely_typo(name, key)) {
        throw ConfigError(pointer(name) + ": unknown key '" + name + "'; did you mean '" +
                          std::string(key) + "'?");
      }
    }
  }
  throw ConfigError(pointer(key) + ": missing; expected " + expected);
}

const nlohmann::json* ParamReader::find(std::string_view key) {
  known_.emplace(key);
  if (!params_.is_object()) return nullptr;
  const auto it = params_.find(key);
  return it == params_.end() ? nullptr : &*it;
}

bool ParamReader::has(std::string_view key) { return find(key) != nullptr; }

std::string ParamReader::pointer(std::string_view key) const {
  return pointer_ + "/" + escape_pointer_token(key);
}

double ParamReader::number(std::string_view key, Bound bound, std::string_view unit) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) throw_missing(key, bound_text(bound, unit));
  if (!value->is_number() || !within_bound(bound, value->get<double>())) {
    throw ConfigError(pointer(key) + ": found " + shown(*value) + "; expected " +
                      bound_text(bound, unit));
  }
  return value->get<double>();
}

double ParamReader::number_or(std::string_view key, double fallback, Bound bound,
                              std::string_view unit) {
  return has(key) ? number(key, bound, unit) : fallback;
}

std::array<double, 3> ParamReader::axes(std::string_view key, Bound bound, std::string_view unit) {
  const nlohmann::json* value = find(key);
  const std::string expected =
      bound_text(bound, unit) + " for all axes, or an array of 3 such numbers [x, y, z]";
  if (value == nullptr) throw_missing(key, expected);
  if (value->is_number()) {
    if (!within_bound(bound, value->get<double>())) {
      throw ConfigError(pointer(key) + ": found " + shown(*value) + "; expected " + expected);
    }
    const double v = value->get<double>();
    return {v, v, v};
  }
  if (!value->is_array() || value->size() != 3) {
    throw ConfigError(pointer(key) + ": found " + shown(*value) + "; expected " + expected);
  }
  std::array<double, 3> result{};
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& item = (*value)[i];
    if (!item.is_number() || !within_bound(bound, item.get<double>())) {
      throw ConfigError(pointer(key) + "/" + std::to_string(i) + ": found " + shown(item) +
                        "; expected " + bound_text(bound, unit));
    }
    result[i] = item.get<double>();
  }
  return result;
}

std::array<double, 3> ParamReader::axes_or(std::string_view key, std::array<double, 3> fallback,
                                           Bound bound, std::string_view unit) {
  return has(key) ? axes(key, bound, unit) : fallback;
}

bool ParamReader::boolean_or(std::string_view key, bool fallback) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return fallback;
  if (!value->is_boolean()) {
    throw ConfigError(pointer(key) + ": found " + shown(*value) + "; expected true or false");
  }
  return value->get<bool>();
}

std::string ParamReader::text(std::string_view key) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) throw_missing(key, "a non-empty string");
  if (!value->is_string() || value->get<std::string>().empty()) {
    throw ConfigError(pointer(key) + ": found " + shown(*value) + "; expected a non-empty string");
  }
  return value->get<std::string>();
}

std::string ParamReader::text_or(std::string_view key, std::string_view fallback) {
  return has(key) ? text(key) : std::string(fallback);
}

std::string ParamReader::choice_or(std::string_view key, std::string_view fallback,
                                   std::span<const std::string_view> allowed) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::string(fallback);
  std::string options;
  for (std::string_view option : allowed) {
    options += (options.empty() ? "\"" : ", \"") + std::string(option) + "\"";
  }
  if (value->is_string()) {
    const auto text = value->get<std::string>();
    for (std::string_view option : allowed) {
      if (text == option) return text;
    }
  }
  throw ConfigError(pointer(key) + ": found " + shown(*value) + "; expected one of " + options);
}

const nlohmann::json& ParamReader::required(std::string_view key, const std::string& expected) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) throw_missing(key, expected);
  return *value;
}

const nlohmann::json& ParamReader::raw(std::string_view key) {
  static const nlohmann::json null_value;
  const nlohmann::json* value = find(key);
  return value == nullptr ? null_value : *value;
}

void ParamReader::finish() const {
  if (!params_.is_object()) return;
  for (const auto& [key, value] : params_.items()) {
    if (known_.count(key) != 0) continue;
    const std::vector<std::string> names(known_.begin(), known_.end());
    throw ConfigError(pointer(key) + ": " + unknown_key_problem(key, names));
  }
}

}  // namespace stochnav::plugin

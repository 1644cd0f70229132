#pragma once
// Strict reading of a JSON object: a plugin's `params`, or a section of a config: where JSON stops
// (STYLE.md). A factory reads every key into a plain struct, then calls finish(), which rejects
// keys it never asked for. Every error is a ConfigError "<pointer>/<key>: <problem>; expected
// <form>"; a key that is a likely typo of a known one says so: "<pointer>/sigam: unknown key
// 'sigam'; did you mean 'sigma'?" (also when the known key is required and so missing).
//
// Lifetime: a reader refers to its params object (and raw() returns references into it), so the
// object must outlive the reader. A temporary is refused at compile time.

#include <array>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <string>
#include <string_view>

namespace stochnav::plugin {

/// Allowed values of a number.
enum class Bound {
  kAny,          ///< any finite number
  kNonNegative,  ///< >= 0
  kPositive,     ///< > 0
  kOpenUnit,     ///< in (0, 1)
};

/// Whether `value` is finite and within `bound`.
bool within_bound(Bound bound, double value);

/// "a number > 0 (deg/h)": what a value within `bound` looks like, for messages and docs.
std::string bound_description(Bound bound, std::string_view unit);

class ParamReader {
 public:
  /// `params` must be an object or null (read as {}); `pointer` is its JSON pointer. Throws
  /// ConfigError otherwise. Keeps a reference to `params`, which must outlive the reader.
  ParamReader(const nlohmann::json& params, std::string pointer);
  /// A temporary would dangle: keep the params in a named variable first.
  ParamReader(nlohmann::json&& params, std::string pointer) = delete;
  ParamReader(const ParamReader&) = delete;
  ParamReader& operator=(const ParamReader&) = delete;

  /// Declares keys that will be read (e.g. a ParamTable's), so that a typo of one is reported as
  /// a typo even before the reader reaches it, and another declared key is never taken for one.
  void expect(std::string_view key);

  /// Whether the key is present (and marks it known).
  bool has(std::string_view key);

  /// A required number; `unit` is named in messages ("deg/h", "s", "" for none).
  double number(std::string_view key, Bound bound, std::string_view unit);
  double number_or(std::string_view key, double fallback, Bound bound, std::string_view unit);

  /// A number for all three axes or an array [x, y, z].
  std::array<double, 3> axes(std::string_view key, Bound bound, std::string_view unit);
  std::array<double, 3> axes_or(std::string_view key, std::array<double, 3> fallback, Bound bound,
                                std::string_view unit);

  bool boolean_or(std::string_view key, bool fallback);
  /// A required non-empty string.
  std::string text(std::string_view key);
  std::string text_or(std::string_view key, std::string_view fallback);
  /// A string among `allowed`.
  std::string choice_or(std::string_view key, std::string_view fallback,
                        std::span<const std::string_view> allowed);
  /// The value of a required key of any type; ConfigError "missing; expected <expected>" (or a
  /// likely typo of the key) when absent.
  const nlohmann::json& required(std::string_view key, const std::string& expected);
  /// The raw value (null when absent), e.g. a nested object read with its own ParamReader.
  const nlohmann::json& raw(std::string_view key);

  /// The JSON pointer of a key.
  std::string pointer(std::string_view key) const;
  const std::string& pointer() const { return pointer_; }

  /// Throws ConfigError for the first key never asked for: the nearest known key when it is a
  /// likely typo, else the list of known keys.
  void finish() const;

 private:
  const nlohmann::json* find(std::string_view key);
  /// Throws ConfigError: a likely typo of `key` among the keys not read or expected, else
  /// "<pointer>/<key>: missing; expected <expected>".
  [[noreturn]] void throw_missing(std::string_view key, const std::string& expected) const;

  const nlohmann::json& params_;
  std::string pointer_;
  std::set<std::string, std::less<>> known_;
  std::set<std::string, std::less<>> expected_;
};

}  // namespace stochnav::plugin

// ParamReader: strict reading of params objects, and the NIS gate keys shared by every aid.

#include "stochnav/plugin/params.hpp"

#include <gtest/gtest.h>

#include <type_traits>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/nearest_name.hpp"
#include "stochnav/plugin/aid_plugin.hpp"

namespace stochnav::plugin {
namespace {

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(ParamReader, ReadsNumbersAxesChoicesAndRejectsUnknownKeys) {
  const nlohmann::json params = {{"a", 2.5}, {"b", {1, 2, 3}}, {"c", "x"}, {"d", true}};
  ParamReader reader(params, "/aids/0/params");
  EXPECT_EQ(reader.number("a", Bound::kPositive, "m"), 2.5);
  EXPECT_EQ(reader.axes("b", Bound::kAny, ""), (std::array<double, 3>{1, 2, 3}));
  constexpr std::string_view kChoices[] = {"x", "y"};
  EXPECT_EQ(reader.choice_or("c", "y", kChoices), "x");
  EXPECT_EQ(reader.number_or("missing", 7.0, Bound::kAny, ""), 7.0);
  EXPECT_EQ(error_of([&] { reader.finish(); }),
            "/aids/0/params/d: unknown key; expected only a, b, c, missing");
  EXPECT_TRUE(reader.boolean_or("d", false));
  EXPECT_NO_THROW(reader.finish());
}

// A reader refers to its params: a temporary would dangle, so it does not compile.
static_assert(!std::is_constructible_v<ParamReader, nlohmann::json&&, std::string>);
static_assert(std::is_constructible_v<ParamReader, const nlohmann::json&, std::string>);

TEST(ParamReader, ErrorsNameThePointerAndTheExpectedForm) {
  const nlohmann::json params = {{"p", 1.5}, {"s", 3}, {"a/b", -1}};
  ParamReader reader(params, "/x");
  EXPECT_EQ(error_of([&] { reader.number("p", Bound::kOpenUnit, ""); }),
            "/x/p: found 1.5; expected a number in (0, 1)");
  EXPECT_EQ(error_of([&] { reader.text("s"); }), "/x/s: found 3; expected a non-empty string");
  EXPECT_EQ(error_of([&] { reader.number("a/b", Bound::kNonNegative, "s"); }),
            "/x/a~1b: found -1; expected a number >= 0 (s)");
  const nlohmann::json array = nlohmann::json::array();
  EXPECT_EQ(error_of([&] { ParamReader bad(array, "/y"); }),
            "/y: found []; expected an object of parameters");
  const nlohmann::json null_params;
  ParamReader empty(null_params, "/z");
  EXPECT_FALSE(empty.has("anything"));
  EXPECT_NO_THROW(empty.finish());
}

TEST(NisGate, DefaultsToTheChiSquareQuantileAndCanBeOverridden) {
  const nlohmann::json no_params = nlohmann::json::object();
  ParamReader defaults(no_params, "/g");
  const NisGate gate = read_nis_gate(defaults, 1);
  EXPECT_TRUE(gate.enabled);
  EXPECT_NEAR(gate.threshold, 10.8276, 1e-3);  // chi2(1) at 99.9 %
  EXPECT_TRUE(gate.accepts(10.0));
  EXPECT_FALSE(gate.accepts(11.0));
  const nlohmann::json params = {{"nis_probability", 0.99}};
  ParamReader probability(params, "/g");
  EXPECT_NEAR(read_nis_gate(probability, 3).threshold, 11.3449, 1e-3);
  const nlohmann::json explicit_params = {{"nis_threshold", 4.0}, {"nis_gate", false}};
  ParamReader fixed(explicit_params, "/g");
  const NisGate off = read_nis_gate(fixed, 2);
  EXPECT_EQ(off.threshold, 4.0);
  EXPECT_TRUE(off.accepts(1e9));
}

TEST(AidData, ColumnsByNameWithClearErrors) {
  const AidData data("aids.csv", {"t", "zupt"}, {{0.0, 1.0}, {1.0, 0.0}});
  EXPECT_EQ(data.rows(), 2u);
  EXPECT_EQ(data.column("zupt", "/aids/0/params")[0], 1.0);
  EXPECT_EQ(error_of([&] { data.column("rop_mph", "/aids/0/params/column"); }),
            "/aids/0/params/column: aid data aids.csv has no column 'rop_mph'; columns: t, zupt "
            "(give the run an aids file with that column)");
  EXPECT_THROW(AidData("x", {"t"}, {{1.0, 0.5}}), InputError);
}

}  // namespace
}  // namespace stochnav::plugin

namespace stochnav {
namespace {

TEST(NearestName, SuggestsLikelyTyposOnly) {
  EXPECT_EQ(typo_distance("sigam", "sigma"), 1u);  // a swap counts once
  EXPECT_EQ(typo_distance("Tau_C", "tau_c"), 0u);
  const std::vector<std::string> known = {"K", "N", "sigma", "tau_c"};
  EXPECT_EQ(nearest_name("sigam", known), "sigma");
  EXPECT_EQ(nearest_name("tauc", known), "tau_c");
  EXPECT_EQ(nearest_name("x", known), std::nullopt);      // one letter is no typo of another
  EXPECT_EQ(nearest_name("speed", known), std::nullopt);  // too far from every name
  EXPECT_EQ(unknown_key_problem("sigam", known), "unknown key 'sigam'; did you mean 'sigma'?");
  EXPECT_EQ(unknown_key_problem("speed", known), "unknown key; expected only K, N, sigma, tau_c");
}

TEST(ParamReader, TypoOfARequiredKeyIsReportedAsTheTypo) {
  const nlohmann::json params = {{"sigam", 1.0}, {"N", 2.0}};
  plugin::ParamReader reader(params, "/p");
  EXPECT_EQ(plugin::error_of([&] { reader.number("sigma", plugin::Bound::kPositive, "deg/h"); }),
            "/p/sigam: unknown key 'sigam'; did you mean 'sigma'?");
  // A declared key is never taken for a typo of another: "max_q" is one edit from "max_p".
  const nlohmann::json orders = {{"max_q", 1}};
  plugin::ParamReader undeclared(orders, "/p");
  EXPECT_EQ(plugin::error_of([&] { undeclared.number("max_p", plugin::Bound::kAny, ""); }),
            "/p/max_q: unknown key 'max_q'; did you mean 'max_p'?");
  plugin::ParamReader declared(orders, "/p");
  declared.expect("max_q");
  EXPECT_EQ(plugin::error_of([&] { declared.number("max_p", plugin::Bound::kAny, ""); }),
            "/p/max_p: missing; expected a finite number");
}

}  // namespace
}  // namespace stochnav

// ParamTable: one declaration per parameter gives reading with unit conversion, writing,
// describing, comparing and documentation.

#include "stochnav/plugin/param_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stochnav/core/errors.hpp"

namespace stochnav::plugin {
namespace {

using Axes = std::array<double, 3>;

struct ExampleParams {
  Axes sigma{};      ///< rad/s or m/s^2
  double tau_c = 0;  ///< s
  double n = 0;      ///< rad/sqrt(s) or m/s/sqrt(s)
  bool white = false;
};

const ParamTable<ExampleParams> kTable{
    per_axis(&ExampleParams::sigma, "sigma", ParamUnit::of(ParameterDimension::kRate),
             Bound::kPositive, kRequired, "stationary standard deviation"),
    scalar(&ExampleParams::tau_c, "tau_c", ParamUnit::fixed("s"), Bound::kPositive, 10.0,
           "correlation time"),
    scalar(&ExampleParams::n, "N", ParamUnit::of(ParameterDimension::kAnglePerRootTime),
           Bound::kNonNegative, kDerived, "angle random walk"),
    flag(&ExampleParams::white, "white", true, "add white noise"),
};

constexpr double kRadPerSecondPerDegPerHour = std::numbers::pi / 180.0 / 3600.0;

template <class Params>
std::string parse_error(const ParamTable<Params>& table, const nlohmann::json& json) {
  try {
    table.parse(json, "/p", Quantity::kAngularRate);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(accepted)";
}

std::string error_of(const nlohmann::json& json) { return parse_error(kTable, json); }

TEST(ParamTable, ReadsReportingUnitsIntoNaturalUnitsWithDefaults) {
  const nlohmann::json json = {{"sigma", {1.0, 2.0, 3.0}}};
  const ExampleParams gyro = kTable.parse(json, "/p", Quantity::kAngularRate);
  EXPECT_DOUBLE_EQ(gyro.sigma[1], 2.0 * kRadPerSecondPerDegPerHour);
  EXPECT_EQ(gyro.tau_c, 10.0);
  EXPECT_TRUE(std::isnan(gyro.n));  // derived by the factory
  EXPECT_TRUE(gyro.white);
  const ExampleParams accel = kTable.parse(json, "/p", Quantity::kSpecificForce);
  EXPECT_DOUBLE_EQ(accel.sigma[2], 3.0 / 3600.0);  // m/s/h -> m/s^2
}

TEST(ParamTable, WritesWhatItReadsAndComparesWithinTolerance) {
  const nlohmann::json json = {{"sigma", 0.5}, {"tau_c", 20}, {"N", 0.05}, {"white", false}};
  const ExampleParams params = kTable.parse(json, "/p", Quantity::kAngularRate);
  const nlohmann::json written = kTable.to_json(params, Quantity::kAngularRate);
  EXPECT_EQ(written["sigma"].size(), 3u);
  EXPECT_NEAR(written["sigma"][0].get<double>(), 0.5, 1e-15);
  EXPECT_EQ(written["white"], false);
  const ExampleParams again = kTable.parse(written, "/p", Quantity::kAngularRate);
  EXPECT_TRUE(kTable.equal(params, again, 1e-12));
  ExampleParams other = params;
  other.sigma[2] *= 1.001;
  EXPECT_FALSE(kTable.equal(params, other, 1e-6));
  EXPECT_TRUE(kTable.equal(params, other, 1e-2));
  other = params;
  other.white = true;
  EXPECT_FALSE(kTable.equal(params, other, 1.0));
  EXPECT_EQ(kTable.describe(params, Quantity::kAngularRate),
            "sigma = 0.5 deg/h, tau_c = 20 s, N = 0.05 deg/sqrt(h), white = false");
}

TEST(ParamTable, ErrorsNameThePointerTheUnitAndTypos) {
  EXPECT_EQ(error_of({{"tau_c", 1}}).rfind("/p/sigma: missing; expected a number > 0 (deg/h)", 0),
            0u);
  EXPECT_EQ(error_of({{"sigma", 1}, {"tau_c", 0}}), "/p/tau_c: found 0; expected a number > 0 (s)");
  EXPECT_EQ(error_of({{"sigam", 1}}), "/p/sigam: unknown key 'sigam'; did you mean 'sigma'?");
  EXPECT_EQ(error_of({{"sigma", 1}, {"colour", 1}}),
            "/p/colour: unknown key; expected only N, sigma, tau_c, white");
}

TEST(ParamTable, DocumentsEachParameter) {
  const auto lines = kTable.documentation(Quantity::kAngularRate);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0],
            "sigma: stationary standard deviation; a number > 0 (deg/h), per axis (a number or "
            "[x, y, z]), required");
  EXPECT_EQ(lines[1], "tau_c: correlation time; a number > 0 (s), default 10 s");
  EXPECT_EQ(lines[3], "white: add white noise; true or false, default true");
}

}  // namespace
}  // namespace stochnav::plugin

// The other kinds of entries: names, integers, strings, series, nested objects, lifted tables.
namespace stochnav::plugin {
namespace {
namespace kinds {

enum class Method { kBurg, kYuleWalker };

struct Inner {
  double height_m = 0.0;
  std::string column;
};

const ParamTable<Inner> kInnerTable{
    scalar(&Inner::height_m, "height_m", ParamUnit::fixed("m"), Bound::kAny, 0.0, "height"),
    text(&Inner::column, "column", "fix_height_m", "column name"),
};

struct Gate {
  double probability = 0.0;
};

const ParamTable<Gate> kGateTable{
    scalar(&Gate::probability, "probability", ParamUnit::fixed(""), Bound::kOpenUnit, 0.5,
           "gate probability"),
};

struct Params {
  Method method = Method::kBurg;
  int order = 0;
  std::vector<double> t;
  std::array<std::vector<double>, 3> n;
  std::vector<Method> methods;
  Inner site;
  std::array<Inner, 3> axes;
  Gate gate;
};

const auto kKindsTable =
    ParamTable<Params>{
        choice(&Params::method, "method",
               {{"burg", Method::kBurg}, {"yule_walker", Method::kYuleWalker}}, Method::kBurg,
               "estimator"),
        integer(&Params::order, "order", 1, 20, 8, "largest order"),
        series(&Params::t, "t", ParamUnit::fixed("s"), {.ascending = true}, "analysis times"),
        axis_series(&Params::n, "N", ParamUnit::of(ParameterDimension::kAnglePerRootTime),
                    Bound::kNonNegative, &Params::t, "t", "N at each time"),
        choices(&Params::methods, "methods",
                {{"burg", Method::kBurg}, {"yule_walker", Method::kYuleWalker}}, {Method::kBurg},
                "estimators tried"),
        group(&Params::site, "site", kInnerTable, Absent::kKeep, "the site"),
        axis_groups(&Params::axes, "axes", kInnerTable, "per axis"),
    }
        .plus(lift(&Params::gate, kGateTable));

const nlohmann::json kGood = {
    {"method", "yule_walker"},
    {"t", {0.0, 10.0}},
    {"N", {{0.1, 0.2}, {0.1, 0.2}, {0.3, 0.3}}},
    {"axes", {{{"height_m", 1.0}}, nlohmann::json::object(), {{"column", "z"}}}},
    {"probability", 0.9},
};

std::string error_with(const std::string& key, const nlohmann::json& value) {
  nlohmann::json json = kGood;
  if (value.is_null()) {
    json.erase(key);
  } else {
    json[key] = value;
  }
  return parse_error(kKindsTable, json);
}

TEST(ParamTableKinds, ReadWriteRoundTrip) {
  Params params;
  params.site = {7.0, "c"};  // kept: "site" is absent
  kKindsTable.parse_into(kGood, "/p", Quantity::kAngularRate, params);
  EXPECT_EQ(params.method, Method::kYuleWalker);
  EXPECT_EQ(params.order, 8);
  EXPECT_EQ(params.t, (std::vector<double>{0.0, 10.0}));
  ASSERT_EQ(params.n[2].size(), 2u);
  EXPECT_DOUBLE_EQ(params.n[2][1], 0.3 * std::numbers::pi / 180.0 / 60.0);  // deg/sqrt(h)
  EXPECT_EQ(params.methods, std::vector<Method>{Method::kBurg});
  EXPECT_EQ(params.site.height_m, 7.0);
  EXPECT_EQ(params.axes[0].height_m, 1.0);
  EXPECT_EQ(params.axes[1].column, "fix_height_m");
  EXPECT_EQ(params.axes[2].column, "z");
  EXPECT_EQ(params.gate.probability, 0.9);

  const nlohmann::json written = kKindsTable.to_json(params, Quantity::kAngularRate);
  EXPECT_EQ(written["method"], "yule_walker");
  EXPECT_EQ(written["site"]["height_m"], 7.0);
  EXPECT_EQ(written["probability"], 0.9);
  const Params again = kKindsTable.parse(written, "/p", Quantity::kAngularRate);
  EXPECT_TRUE(kKindsTable.equal(params, again, 1e-12));
  Params other = again;
  other.t.push_back(20.0);
  EXPECT_FALSE(kKindsTable.equal(params, other, 1.0));
  other = again;
  other.axes[2].column = "w";
  EXPECT_FALSE(kKindsTable.equal(params, other, 1.0));

  const std::string text = kKindsTable.describe(params, Quantity::kAngularRate);
  EXPECT_NE(text.find("method = yule_walker, order = 8, t = [0, 10] s"), std::string::npos) << text;
  EXPECT_NE(text.find("site = {height_m = 7 m, column = \"c\"}"), std::string::npos) << text;
  EXPECT_NE(text.find("probability = 0.9"), std::string::npos) << text;
}

TEST(ParamTableKinds, ErrorsNameThePointer) {
  EXPECT_EQ(error_with("method", "brug"),
            "/p/method: found \"brug\"; expected one of \"burg\", \"yule_walker\"");
  EXPECT_EQ(error_with("order", 2.5), "/p/order: found 2.5; expected an integer in [1, 20]");
  EXPECT_EQ(error_with("order", 21), "/p/order: found 21.0; expected an integer in [1, 20]");
  EXPECT_EQ(error_with("t", {0.0, 0.0})
                .rfind("/p/t/1: found 0.0; expected a finite number (s) "
                       "greater than the one before",
                       0),
            0u);
  EXPECT_EQ(error_with("N", {{0.1}, {0.1, 0.2}, {0.1, 0.2}}),
            "/p/N/0: found [0.1]; expected an array of 2 values (one per value of /p/t)");
  EXPECT_EQ(error_with("N", {{0.1, -1.0}, {0.1, 0.2}, {0.1, 0.2}}),
            "/p/N/0/1: found -1.0; expected a number >= 0 (deg/sqrt(h))");
  EXPECT_EQ(error_with("methods", {"burg", "burg"}).rfind("/p/methods/1: found \"burg\"", 0), 0u);
  EXPECT_EQ(error_with("site", {{"height_m", "high"}}),
            "/p/site/height_m: found \"high\"; expected a finite number (m)");
  EXPECT_EQ(error_with("axes", nlohmann::json::array({nlohmann::json::object()})),
            "/p/axes: found [{}]; expected an array of 3 objects [x, y, z]");
  EXPECT_EQ(
      error_with("axes", {{{"colum", "a"}}, nlohmann::json::object(), nlohmann::json::object()}),
      "/p/axes/0/colum: unknown key 'colum'; did you mean 'column'?");
  EXPECT_EQ(error_with("probability", 1.0),
            "/p/probability: found 1.0; expected a number in (0, 1)");
  // A typo of a required key of any kind is named as one.
  nlohmann::json typo = kGood;
  typo.erase("t");
  typo["tt"] = {0.0, 10.0};
  EXPECT_EQ(parse_error(kKindsTable, typo), "/p/tt: unknown key 'tt'; did you mean 't'?");
}

TEST(ParamTableKinds, DocumentsEveryKind) {
  const auto lines = kKindsTable.documentation(Quantity::kAngularRate);
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines[0], "method: estimator; one of \"burg\", \"yule_walker\", default \"burg\"");
  EXPECT_EQ(lines[1], "order: largest order; an integer in [1, 20], default 8");
  EXPECT_EQ(lines[2], "t: analysis times; an ascending array of a finite number (s), required");
  EXPECT_EQ(lines[7], "probability: gate probability; a number in (0, 1), default 0.5");
}

}  // namespace kinds
}  // namespace
}  // namespace stochnav::plugin

// TabulatedAid (plugin/tabulated_aid.hpp): the gate keys lifted into the table, describe() with
// and without a detail, params() read back into an equal aid, equals() telling parameters apart.

#include "stochnav/plugin/tabulated_aid.hpp"

#include <gtest/gtest.h>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav::plugin {
namespace {

struct SpeedParams {
  double sigma_mps;  ///< m/s
  NisGateParams gate;
};

const auto kSpeedTable = aid_param_table<SpeedParams>({
    scalar(&SpeedParams::sigma_mps, "sigma_mps", ParamUnit::fixed("m/s"), Bound::kPositive, 0.01,
           "1-sigma of the speed"),
});

// A speed aid of two components, in process (no plugin library).
class SpeedAid final : public TabulatedAid<SpeedParams> {
 public:
  SpeedAid(const SpeedParams& params, std::string detail)
      : TabulatedAid(kSpeedTable, params, 2), detail_(std::move(detail)) {}
  std::string_view type() const override { return "speed"; }
  int measurement_size() const override { return 2; }
  bool has_measurement(double) const override { return true; }
  bool measure(double, const NavState& state, const ImuSample&,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    residual = state.v_n.head<2>();
    h.setZero();
    h.block<2, 2>(0, core_state::kVelocity).setIdentity();
    r = parameters().sigma_mps * parameters().sigma_mps * Eigen::Matrix2d::Identity();
    return true;
  }

 private:
  std::string detail() const override { return detail_; }
  std::string detail_;
};

SpeedAid make_speed(const nlohmann::json& json, std::string detail = "") {
  AidContext context;
  context.params_pointer = "/aids/1/params";
  return SpeedAid(parse_aid_params(kSpeedTable, json, context), std::move(detail));
}

TEST(TabulatedAid, DescribesItsTypeDetailAndParams) {
  EXPECT_EQ(make_speed({{"sigma_mps", 0.5}}).describe().rfind("speed: sigma_mps = 0.5 m/s, ", 0),
            0u);
  EXPECT_EQ(make_speed(nlohmann::json::object(), "horizontal speed")
                .describe()
                .rfind("speed: horizontal speed; sigma_mps = 0.01 m/s, nis_gate = true", 0),
            0u);
}

TEST(TabulatedAid, GateFollowsTheLiftedKeys) {
  EXPECT_NEAR(make_speed(nlohmann::json::object()).gate().threshold, chi_square_quantile(0.999, 2),
              1e-12);
  EXPECT_EQ(make_speed({{"nis_threshold", 9.0}}).gate().threshold, 9.0);
  EXPECT_FALSE(make_speed({{"nis_gate", false}}).gate().enabled);
  try {
    make_speed({{"nis_treshold", 9.0}});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/aids/1/params/nis_treshold: unknown key"),
              std::string::npos)
        << error.what();
  }
}

TEST(TabulatedAid, ParamsReadBackIntoAnEqualAid) {
  for (const nlohmann::json& json :
       {nlohmann::json::object(), nlohmann::json{{"sigma_mps", 0.2}, {"nis_threshold", 7.5}},
        nlohmann::json{{"nis_probability", 0.99}, {"nis_gate", false}}}) {
    const SpeedAid aid = make_speed(json);
    const SpeedAid again = make_speed(aid.params());
    EXPECT_TRUE(aid.equals(again, 1e-12)) << aid.params().dump();
    EXPECT_TRUE(again.equals(aid, 1e-12)) << aid.params().dump();
    EXPECT_EQ(again.describe(), aid.describe());
  }
  EXPECT_FALSE(make_speed({{"sigma_mps", 0.2}}).params().contains("nis_threshold"));
  EXPECT_FALSE(make_speed({{"sigma_mps", 0.2}}).equals(make_speed({{"sigma_mps", 0.3}}), 1e-6));
  EXPECT_FALSE(
      make_speed(nlohmann::json::object()).equals(make_speed({{"nis_threshold", 9.0}}), 1e-6));
}

}  // namespace
}  // namespace stochnav::plugin

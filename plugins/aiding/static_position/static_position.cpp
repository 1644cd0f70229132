// Aid plugin "static_position": the tool does not move (vibration-table experiments, the
// paper's Eq. 25). At a fixed rate it measures the position error against the known site and
// the velocity against zero:
//   z = [dr (ENU, m, estimate - site); v_n (m/s)],  H = [I 0 0 0 0; 0 I 0 0 0],
//   R = diag(sigma_position^2 I, sigma_velocity^2 I),
// with dr = (remainder(lon - lon_site, 2 pi) (R_N + h_site) cos(lat_site),
// (lat - lat_site) (R_M + h_site), h - h_site), the radii at the site (ins/earth.hpp). With
// "zero_velocity": false only the position rows: z = dr, H = [I 0 0 0 0],
// R = sigma_position^2 I (measurement size 3).
//
// params:
//   "rate_hz"             measurement rate (Hz), > 0, default 1
//   "sigma_position_m"    1-sigma of the site position (m), > 0, default 0.01
//   "zero_velocity"       bool, default true: also measure the velocity against zero
//   "sigma_velocity_mps"  1-sigma of the zero velocity (m/s), > 0, default 0.001
//   "site"                {"latitude_deg", "longitude_deg", "height_m"}; default: the run's
//                         initial position
//   gate keys: see plugin/aid_plugin.hpp (read_nis_gate)

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "stochnav/core/angles.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/aid_schedule.hpp"
#include "stochnav/plugin/param_table.hpp"
#include "stochnav/plugin/params.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "stochnav/plugin/tabulated_aid.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"

namespace {

namespace cs = stochnav::plugin::core_state;
using stochnav::kRadPerDeg;
using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;

struct Site {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double height_m = 0.0;  ///< above the WGS-84 ellipsoid
};

const stochnav::plugin::ParamTable<Site> kSiteTable{
    scalar(&Site::latitude_deg, "latitude_deg", ParamUnit::fixed("deg"), Bound::kAny,
           stochnav::plugin::kRequired, "latitude"),
    scalar(&Site::longitude_deg, "longitude_deg", ParamUnit::fixed("deg"), Bound::kAny,
           stochnav::plugin::kRequired, "longitude"),
    scalar(&Site::height_m, "height_m", ParamUnit::fixed("m"), Bound::kAny, 0.0,
           "height above the WGS-84 ellipsoid"),
};

struct StaticPositionParams {
  double rate_hz;             ///< Hz
  double sigma_position_m;    ///< m
  bool zero_velocity;         ///< also measure the velocity against zero
  double sigma_velocity_mps;  ///< m/s
  Site site;                  ///< the factory's default: the run's initial position
  stochnav::plugin::NisGateParams gate;
};

const auto kStaticPositionTable = stochnav::plugin::aid_param_table<StaticPositionParams>({
    scalar(&StaticPositionParams::rate_hz, "rate_hz", ParamUnit::fixed("Hz"), Bound::kPositive, 1.0,
           "measurement rate"),
    scalar(&StaticPositionParams::sigma_position_m, "sigma_position_m", ParamUnit::fixed("m"),
           Bound::kPositive, 0.01, "1-sigma of the site position"),
    stochnav::plugin::flag(&StaticPositionParams::zero_velocity, "zero_velocity", true,
                           "also measure the velocity against zero"),
    scalar(&StaticPositionParams::sigma_velocity_mps, "sigma_velocity_mps", ParamUnit::fixed("m/s"),
           Bound::kPositive, 0.001, "1-sigma of the zero velocity"),
    group(&StaticPositionParams::site, "site", kSiteTable, stochnav::plugin::Absent::kKeep,
          "the known position; default the run's initial position"),
});

class StaticPositionAid final : public stochnav::plugin::TabulatedAid<StaticPositionParams> {
 public:
  StaticPositionAid(const StaticPositionParams& params, double start_s)
      : TabulatedAid(kStaticPositionTable, params, params.zero_velocity ? 6 : 3),
        latitude_rad_(params.site.latitude_deg * kRadPerDeg),
        longitude_rad_(params.site.longitude_deg * kRadPerDeg),
        schedule_(stochnav::plugin::AidSchedule::periodic(start_s, params.rate_hz)) {}

  std::string_view type() const override { return "static_position"; }
  int measurement_size() const override { return parameters().zero_velocity ? 6 : 3; }
  bool has_measurement(double t_s) const override { return schedule_.due(t_s); }

  bool measure(double, const stochnav::NavState& state, const stochnav::plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const StaticPositionParams& params = parameters();
    const stochnav::EarthRadii radii = stochnav::earth_radii(latitude_rad_);
    residual(0) = std::remainder(state.longitude_rad - longitude_rad_, 2 * std::numbers::pi) *
                  (radii.transverse_m + params.site.height_m) * std::cos(latitude_rad_);
    residual(1) = (state.latitude_rad - latitude_rad_) * (radii.meridian_m + params.site.height_m);
    residual(2) = state.height_m - params.site.height_m;
    h.setZero();
    h.block<3, 3>(0, cs::kPosition).setIdentity();
    r.setZero();
    r.diagonal().head<3>().setConstant(params.sigma_position_m * params.sigma_position_m);
    if (params.zero_velocity) {
      residual.segment<3>(3) = state.v_n;
      h.block<3, 3>(3, cs::kVelocity).setIdentity();
      r.diagonal().tail<3>().setConstant(params.sigma_velocity_mps * params.sigma_velocity_mps);
    }
    return true;
  }

 private:
  double latitude_rad_;   ///< of the site
  double longitude_rad_;  ///< of the site
  stochnav::plugin::AidSchedule schedule_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_static_position(
    const nlohmann::json& json, const stochnav::plugin::AidContext& context) {
  StaticPositionParams defaults;
  defaults.site = {context.initial_state.latitude_rad / kRadPerDeg,
                   context.initial_state.longitude_rad / kRadPerDeg,
                   context.initial_state.height_m};
  return std::make_unique<StaticPositionAid>(
      stochnav::plugin::parse_aid_params(kStaticPositionTable, json, context, defaults),
      context.initial_state.t_s);
}

}  // namespace

STOCHNAV_AID_PLUGIN("static_position",
                    "Known fixed position and zero velocity (vibration-table experiments)",
                    make_static_position)
STOCHNAV_PLUGIN_DOCUMENTATION(kStaticPositionTable)

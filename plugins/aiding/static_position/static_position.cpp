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

namespace {

namespace cs = stochnav::plugin::core_state;
using stochnav::kRadPerDeg;
using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;

struct StaticPositionParams {
  double rate_hz;             ///< Hz
  double sigma_position_m;    ///< m
  bool zero_velocity;         ///< also measure the velocity against zero
  double sigma_velocity_mps;  ///< m/s
  double latitude_rad = 0.0;
  double longitude_rad = 0.0;
  double height_m = 0.0;
};

const stochnav::plugin::ParamTable<StaticPositionParams> kStaticPositionTable{
    scalar(&StaticPositionParams::rate_hz, "rate_hz", ParamUnit::fixed("Hz"), Bound::kPositive, 1.0,
           "measurement rate"),
    scalar(&StaticPositionParams::sigma_position_m, "sigma_position_m", ParamUnit::fixed("m"),
           Bound::kPositive, 0.01, "1-sigma of the site position"),
    stochnav::plugin::flag(&StaticPositionParams::zero_velocity, "zero_velocity", true,
                           "also measure the velocity against zero"),
    scalar(&StaticPositionParams::sigma_velocity_mps, "sigma_velocity_mps", ParamUnit::fixed("m/s"),
           Bound::kPositive, 0.001, "1-sigma of the zero velocity"),
};

class StaticPositionAid final : public stochnav::plugin::AidPlugin {
 public:
  StaticPositionAid(const StaticPositionParams& params, stochnav::plugin::NisGate gate,
                    double start_s)
      : AidPlugin(gate),
        params_(params),
        schedule_(stochnav::plugin::AidSchedule::periodic(start_s, params.rate_hz)) {}

  std::string_view type() const override { return "static_position"; }
  int measurement_size() const override { return params_.zero_velocity ? 6 : 3; }
  bool has_measurement(double t_s) const override { return schedule_.due(t_s); }

  bool measure(double, const stochnav::NavState& state, const stochnav::plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const stochnav::EarthRadii radii = stochnav::earth_radii(params_.latitude_rad);
    residual(0) =
        std::remainder(state.longitude_rad - params_.longitude_rad, 2 * std::numbers::pi) *
        (radii.transverse_m + params_.height_m) * std::cos(params_.latitude_rad);
    residual(1) =
        (state.latitude_rad - params_.latitude_rad) * (radii.meridian_m + params_.height_m);
    residual(2) = state.height_m - params_.height_m;
    h.setZero();
    h.block<3, 3>(0, cs::kPosition).setIdentity();
    r.setZero();
    r.diagonal().head<3>().setConstant(params_.sigma_position_m * params_.sigma_position_m);
    if (params_.zero_velocity) {
      residual.segment<3>(3) = state.v_n;
      h.block<3, 3>(3, cs::kVelocity).setIdentity();
      r.diagonal().tail<3>().setConstant(params_.sigma_velocity_mps * params_.sigma_velocity_mps);
    }
    return true;
  }

  std::string describe() const override {
    const std::string velocity = params_.zero_velocity
                                     ? fmt::format(", {} m/s", params_.sigma_velocity_mps)
                                     : std::string(" (position only)");
    return fmt::format(
        "static_position: site {:.7f} deg, {:.7f} deg, {:.3f} m; {} Hz; sigma {} m{}",
        params_.latitude_rad / kRadPerDeg, params_.longitude_rad / kRadPerDeg, params_.height_m,
        params_.rate_hz, params_.sigma_position_m, velocity);
  }

 private:
  StaticPositionParams params_;
  stochnav::plugin::AidSchedule schedule_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_static_position(
    const nlohmann::json& json, const stochnav::plugin::AidContext& context) {
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  StaticPositionParams params;
  kStaticPositionTable.read(reader, params);
  params.latitude_rad = context.initial_state.latitude_rad;
  params.longitude_rad = context.initial_state.longitude_rad;
  params.height_m = context.initial_state.height_m;
  if (reader.has("site")) {
    stochnav::plugin::ParamReader site(reader.raw("site"), reader.pointer("site"));
    params.latitude_rad = site.number("latitude_deg", Bound::kAny, "deg") * kRadPerDeg;
    params.longitude_rad = site.number("longitude_deg", Bound::kAny, "deg") * kRadPerDeg;
    params.height_m = site.number_or("height_m", 0.0, Bound::kAny, "m");
    site.finish();
  }
  const auto gate = stochnav::plugin::read_nis_gate(reader, params.zero_velocity ? 6 : 3);
  reader.finish();
  return std::make_unique<StaticPositionAid>(params, gate, context.initial_state.t_s);
}

}  // namespace

STOCHNAV_AID_PLUGIN("static_position",
                    "Known fixed position and zero velocity (vibration-table experiments)",
                    make_static_position)

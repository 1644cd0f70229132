// Aid plugin "inclination_survey": the tool's inclination from an independent survey (a
// single-shot or an accelerometer-only survey at a connection), one value per row of the aid
// data, compared with the inclination of the estimated attitude.
//   I(C_nb) = atan2(sqrt(u_e^2 + u_n^2), -u_u),  u = C_nb z_b (the tool axis, ENU)
//   z = I(C_nb_est) - I_measured                              (rad)
//   H = [0, 0, dI/du [u x], 0, 0]                              (1 x 15, attitude columns)
//       dI/du = [-u_u u_e / s, -u_u u_n / s, s],  s = sin I = sqrt(u_e^2 + u_n^2)
//       since C_nb_est = (I - [phi x]) C_nb gives u_est = u - phi x u = u + [u x] phi
//   R = sigma^2                                                (rad^2)
// No measurement below an inclination of 1e-6 rad, where I is not differentiable.
//
// params:
//   "column"     aid-data column of the surveyed inclination (deg), default "inclination_deg"
//   "sigma_deg"  1-sigma of the surveyed inclination (deg), > 0, default 0.1
//   gate keys: see stochnav/plugin/aid_plugin.hpp

#include <cmath>
#include <numbers>

#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/aid_schedule.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "stochnav/plugin/tabulated_aid.hpp"

namespace {

namespace cs = stochnav::plugin::core_state;
using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
constexpr double kSmallestSinInclination = 1e-6;

struct SurveyParams {
  std::string column;  ///< aid-data column, deg
  double sigma_deg;    ///< deg
  stochnav::plugin::NisGateParams gate;
};

const auto kSurveyTable = stochnav::plugin::aid_param_table<SurveyParams>({
    stochnav::plugin::text(&SurveyParams::column, "column", "inclination_deg",
                           "aid-data column of the surveyed inclination (deg)"),
    scalar(&SurveyParams::sigma_deg, "sigma_deg", ParamUnit::fixed("deg"), Bound::kPositive, 0.1,
           "1-sigma of the surveyed inclination"),
});

class InclinationSurvey final : public stochnav::plugin::TabulatedAid<SurveyParams> {
 public:
  InclinationSurvey(const SurveyParams& params, std::span<const double> times_s,
                    std::span<const double> inclination_deg)
      : TabulatedAid(kSurveyTable, params, 1),
        schedule_(stochnav::plugin::AidSchedule::at_rows(times_s)),
        inclination_deg_(inclination_deg) {}

  std::string_view type() const override { return "inclination_survey"; }
  int measurement_size() const override { return 1; }
  bool has_measurement(double t_s) const override { return schedule_.due(t_s); }

  bool measure(double t_s, const stochnav::NavState& state, const stochnav::plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const auto row = schedule_.row_at(t_s);
    if (!row) return false;
    const Eigen::Vector3d u = state.q_nb * Eigen::Vector3d::UnitZ();
    const double sin_inclination = std::hypot(u.x(), u.y());
    if (sin_inclination < kSmallestSinInclination) return false;
    residual(0) = std::atan2(sin_inclination, -u.z()) - inclination_deg_[*row] * kRadPerDeg;
    const Eigen::RowVector3d d_inclination_d_axis(-u.z() * u.x() / sin_inclination,
                                                  -u.z() * u.y() / sin_inclination,
                                                  sin_inclination);
    Eigen::Matrix3d axis_cross;  // [u x]
    axis_cross << 0.0, -u.z(), u.y(), u.z(), 0.0, -u.x(), -u.y(), u.x(), 0.0;
    h.setZero();
    h.block<1, 3>(0, cs::kAttitude) = d_inclination_d_axis * axis_cross;
    const double sigma_rad = parameters().sigma_deg * kRadPerDeg;
    r(0, 0) = sigma_rad * sigma_rad;
    return true;
  }

 private:
  std::string detail() const override { return "surveyed inclination against the attitude's"; }

  stochnav::plugin::AidSchedule schedule_;
  std::span<const double> inclination_deg_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_inclination_survey(
    const nlohmann::json& json, const stochnav::plugin::AidContext& context) {
  const SurveyParams params = stochnav::plugin::parse_aid_params(kSurveyTable, json, context);
  return std::make_unique<InclinationSurvey>(
      params, context.data->time_s(),
      context.data->column(params.column, context.params_pointer + "/column"));
}

}  // namespace

STOCHNAV_AID_PLUGIN("inclination_survey",
                    "Surveyed inclination (deg) from an aid-data column against the attitude",
                    make_inclination_survey)
// Optional: the params reference `stochnav plugins doc` prints, from the same table.
STOCHNAV_PLUGIN_DOCUMENTATION(kSurveyTable)

// Aid plugin "position_fix": position fixes with their sigmas from the run's aid data (GNSS at
// the surface, a tie-on point, a gyro-survey station). At every row of the aid data that carries
// a fix, the position error of the estimate against the fix, in ENU metres at the fix:
//   z = [remainder(lon_est - lon_fix, 2 pi) (R_N + h_fix) cos(lat_fix);
//        (lat_est - lat_fix) (R_M + h_fix);
//        h_est - h_fix]                                    (m, ENU, estimate - fix)
//   H = [I 0 0 0 0],  R = diag(sigma_east^2, sigma_north^2, sigma_up^2)
// with R_M, R_N the radii of curvature at lat_fix (ins/earth.hpp). Every row of AidData has a
// value in every column (no NaN or empty cells), so a row carries a fix only when all three of
// its sigmas are > 0: write 0 (or a negative value) in the sigma columns of the rows without one.
//
// params:
//   "columns"  optional object renaming the aid-data columns; keys and defaults:
//              "latitude_deg": "fix_latitude_deg", "longitude_deg": "fix_longitude_deg",
//              "height_m": "fix_height_m" (height above the WGS-84 ellipsoid),
//              "sigma_east_m": "fix_sigma_east_m", "sigma_north_m": "fix_sigma_north_m",
//              "sigma_up_m": "fix_sigma_up_m"
//   gate keys: see plugin/aid_plugin.hpp (read_nis_gate)

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>

#include "stochnav/core/angles.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/aid_schedule.hpp"
#include "stochnav/plugin/param_table.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "stochnav/plugin/tabulated_aid.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"

namespace {

namespace cs = stochnav::plugin::core_state;
using stochnav::kRadPerDeg;

// The names of the six aid-data columns.
struct ColumnNames {
  std::string latitude_deg, longitude_deg, height_m, sigma_east_m, sigma_north_m, sigma_up_m;
};

const stochnav::plugin::ParamTable<ColumnNames> kColumnTable{
    stochnav::plugin::text(&ColumnNames::latitude_deg, "latitude_deg", "fix_latitude_deg",
                           "column of the fix latitude (deg)"),
    stochnav::plugin::text(&ColumnNames::longitude_deg, "longitude_deg", "fix_longitude_deg",
                           "column of the fix longitude (deg)"),
    stochnav::plugin::text(&ColumnNames::height_m, "height_m", "fix_height_m",
                           "column of the fix height above the WGS-84 ellipsoid (m)"),
    stochnav::plugin::text(&ColumnNames::sigma_east_m, "sigma_east_m", "fix_sigma_east_m",
                           "column of the east 1-sigma (m)"),
    stochnav::plugin::text(&ColumnNames::sigma_north_m, "sigma_north_m", "fix_sigma_north_m",
                           "column of the north 1-sigma (m)"),
    stochnav::plugin::text(&ColumnNames::sigma_up_m, "sigma_up_m", "fix_sigma_up_m",
                           "column of the up 1-sigma (m)"),
};

struct PositionFixParams {
  ColumnNames columns;
  stochnav::plugin::NisGateParams gate;
};

const auto kPositionFixTable = stochnav::plugin::aid_param_table<PositionFixParams>({
    group(&PositionFixParams::columns, "columns", kColumnTable, stochnav::plugin::Absent::kDefaults,
          "names of the aid-data columns"),
});

struct FixColumns {
  std::span<const double> latitude_deg;
  std::span<const double> longitude_deg;
  std::span<const double> height_m;
  std::span<const double> sigma_east_m;
  std::span<const double> sigma_north_m;
  std::span<const double> sigma_up_m;
};

bool carries_fix(const FixColumns& columns, std::size_t row) {
  return columns.sigma_east_m[row] > 0.0 && columns.sigma_north_m[row] > 0.0 &&
         columns.sigma_up_m[row] > 0.0;
}

class PositionFixAid final : public stochnav::plugin::TabulatedAid<PositionFixParams> {
 public:
  PositionFixAid(const PositionFixParams& params, std::span<const double> times_s,
                 const FixColumns& columns, std::size_t fix_count)
      : TabulatedAid(kPositionFixTable, params, 3),
        schedule_(stochnav::plugin::AidSchedule::at_rows(times_s)),
        columns_(columns),
        fix_count_(fix_count) {}

  std::string_view type() const override { return "position_fix"; }
  int measurement_size() const override { return 3; }

  bool has_measurement(double t_s) const override {
    const auto row = schedule_.row_at(t_s);
    return row && carries_fix(columns_, *row);
  }

  bool measure(double t_s, const stochnav::NavState& state, const stochnav::plugin::ImuSample&,
               Eigen::Ref<Eigen::VectorXd> residual, Eigen::Ref<Eigen::MatrixXd> h,
               Eigen::Ref<Eigen::MatrixXd> r) const override {
    const auto row = schedule_.row_at(t_s);
    if (!row || !carries_fix(columns_, *row)) return false;
    const double latitude_rad = columns_.latitude_deg[*row] * kRadPerDeg;
    const double longitude_rad = columns_.longitude_deg[*row] * kRadPerDeg;
    const double height_m = columns_.height_m[*row];
    const stochnav::EarthRadii radii = stochnav::earth_radii(latitude_rad);
    residual(0) = std::remainder(state.longitude_rad - longitude_rad, 2 * std::numbers::pi) *
                  (radii.transverse_m + height_m) * std::cos(latitude_rad);
    residual(1) = (state.latitude_rad - latitude_rad) * (radii.meridian_m + height_m);
    residual(2) = state.height_m - height_m;
    h.setZero();
    h.block<3, 3>(0, cs::kPosition).setIdentity();
    r.setZero();
    r(0, 0) = columns_.sigma_east_m[*row] * columns_.sigma_east_m[*row];
    r(1, 1) = columns_.sigma_north_m[*row] * columns_.sigma_north_m[*row];
    r(2, 2) = columns_.sigma_up_m[*row] * columns_.sigma_up_m[*row];
    return true;
  }

 private:
  std::string detail() const override {
    return fmt::format("{} position fixes from the aid data, ENU sigmas per row", fix_count_);
  }

  stochnav::plugin::AidSchedule schedule_;
  FixColumns columns_;
  std::size_t fix_count_;
};

std::unique_ptr<stochnav::plugin::AidPlugin> make_position_fix(
    const nlohmann::json& json, const stochnav::plugin::AidContext& context) {
  const PositionFixParams params =
      stochnav::plugin::parse_aid_params(kPositionFixTable, json, context);
  const stochnav::plugin::AidData& data = *context.data;
  // A missing column is reported at the key that renames it ("<params>/columns/latitude_deg"),
  // whether or not the params have it: that is where the user fixes it.
  const auto column = [&](const std::string& name, std::string_view key) {
    return data.column(name, context.params_pointer + "/columns/" + std::string(key));
  };
  const ColumnNames& names = params.columns;
  const FixColumns columns{
      column(names.latitude_deg, "latitude_deg"),   column(names.longitude_deg, "longitude_deg"),
      column(names.height_m, "height_m"),           column(names.sigma_east_m, "sigma_east_m"),
      column(names.sigma_north_m, "sigma_north_m"), column(names.sigma_up_m, "sigma_up_m")};
  std::size_t fix_count = 0;
  for (std::size_t row = 0; row < data.rows(); ++row) {
    if (carries_fix(columns, row)) ++fix_count;
  }
  return std::make_unique<PositionFixAid>(params, data.time_s(), columns, fix_count);
}

}  // namespace

STOCHNAV_AID_PLUGIN("position_fix",
                    "Position fixes with per-row ENU sigmas from the aid data (GNSS, tie-on, "
                    "survey station)",
                    make_position_fix)
STOCHNAV_PLUGIN_DOCUMENTATION(kPositionFixTable)

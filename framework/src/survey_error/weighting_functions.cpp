// The weighting functions as the ISCWSA MWD Rev5 document writes them (azimuth weights
// multiplied by sin I, weighting_functions.hpp), and those of the OWSG gyro tool models
// GYRO-NS-CT, GYRO-NS and GYRO-MWD (rev 5, 2020; their accelerometer terms and stationary
// gyrocompass terms after Torkildsen et al., SPE 90408). Notation: I inclination, AzT true and AzM
// magnetic azimuth, dip the magnetic dip, G gravity, B the total field, Bh = B cos(dip), Omega the
// Earth rate, lat the latitude.

#include "stochnav/survey_error/weighting_functions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stochnav::survey_error {
namespace {

/// XYM3E / XYM4E: random misalignments grow for survey intervals under 10 m,
/// max(1, sqrt(10 m / dMD)).
double short_interval_factor(const StationGeometry& station) {
  const double interval_m = station.md_m - station.previous_md_m;
  return interval_m > 0.0 ? std::max(1.0, std::sqrt(10.0 / interval_m)) : 1.0;
}

/// XCLA: sin(I) times the larger of the azimuth change seen over the leg (its sine; ignored
/// when the previous station is near vertical, where its azimuth means nothing) and the default
/// tortuosity over the leg divided by sin(I).
double unseen_azimuthal_turn(const StationGeometry& station, const WellParameters& well,
                             double tortuosity_rad_per_m) {
  const double interval_m = station.md_m - station.previous_md_m;
  double seen = 0.0;
  if (station.previous_inclination_rad >= well.vertical_inc_limit_rad) {
    const double change = std::remainder(
        station.true_azimuth_rad - station.previous_true_azimuth_rad, 2.0 * std::numbers::pi);
    seen = std::abs(std::sin(station.inclination_rad) * std::sin(std::abs(change)));
  }
  return std::max(seen, tortuosity_rad_per_m * interval_m);
}

/// The horizontal Earth rate a gyrocompass measures north against (rad/s).
double horizontal_earth_rate_rad_s(const WellParameters& well) {
  return well.earth_rate_rad_s * std::cos(well.latitude_rad);
}

/// GXY-B1: an x-y gyro bias along the high side, seen through cos I.
double gxy_b1_azimuth_s(const StationGeometry& station, const WellParameters& well) {
  return std::sin(station.true_azimuth_rad) /
         (horizontal_earth_rate_rad_s(well) * std::cos(station.inclination_rad));
}

/// GXY-B2: an x-y gyro bias along the lateral axis.
double gxy_b2_azimuth_s(const StationGeometry& station, const WellParameters& well) {
  return std::cos(station.true_azimuth_rad) / horizontal_earth_rate_rad_s(well);
}

/// GXY-G1: a g-dependent x-y gyro error along the gravity component across the tool.
double gxy_g1_azimuth_s(const StationGeometry& station, const WellParameters& well) {
  return std::cos(station.true_azimuth_rad) * std::sin(station.inclination_rad) /
         horizontal_earth_rate_rad_s(well);
}

/// GXY-G4: a g-dependent (mass-unbalance) x-y gyro error, growing with tan I.
double gxy_g4_azimuth_s(const StationGeometry& station, const WellParameters& well) {
  return std::sin(station.true_azimuth_rad) * std::tan(station.inclination_rad) /
         horizontal_earth_rate_rad_s(well);
}

/// GXY-RN per unit of reduced rate noise (NRF sigma): white rate noise on both x-y gyros,
/// seen through the horizontal Earth rate.
double gxy_rn_azimuth_s(const StationGeometry& station, const WellParameters& well) {
  const double cos_a = std::cos(station.true_azimuth_rad);
  const double sin_i = std::sin(station.inclination_rad);
  return std::sqrt(1.0 - cos_a * cos_a * sin_i * sin_i) /
         (horizontal_earth_rate_rad_s(well) * std::cos(station.inclination_rad));
}

}  // namespace

bool is_gyrocompass_weighting(WeightingFunction function) {
  switch (function) {
    case WeightingFunction::kGxyB1:
    case WeightingFunction::kGxyB2:
    case WeightingFunction::kGxyG1:
    case WeightingFunction::kGxyG4:
    case WeightingFunction::kGxyRn:
      return true;
    default:
      return false;
  }
}

double gyrocompass_azimuth_weight_s(WeightingFunction function, const StationGeometry& station,
                                    const WellParameters& well) {
  switch (function) {
    case WeightingFunction::kGxyB1:
      return gxy_b1_azimuth_s(station, well);
    case WeightingFunction::kGxyB2:
      return gxy_b2_azimuth_s(station, well);
    case WeightingFunction::kGxyG1:
      return gxy_g1_azimuth_s(station, well);
    case WeightingFunction::kGxyG4:
      return gxy_g4_azimuth_s(station, well);
    case WeightingFunction::kGxyRn:
      return gxy_rn_azimuth_s(station, well);
    default:
      return 0.0;
  }
}

LegReach leg_reach(WeightingFunction function) {
  return function == WeightingFunction::kXcla || function == WeightingFunction::kXclh
             ? LegReach::kWholeLegBefore
             : LegReach::kHalfLegsAround;
}

bool has_near_vertical_form(WeightingFunction function) {
  switch (function) {
    case WeightingFunction::kAbxyTi2:
    case WeightingFunction::kXym3:
    case WeightingFunction::kXym4:
    case WeightingFunction::kXym3e:
    case WeightingFunction::kXym4e:
    case WeightingFunction::kXcla:
      return true;
    default:
      return false;
  }
}

ErrorWeights error_weights(WeightingFunction function, const StationGeometry& station,
                           const WellParameters& well, double tortuosity_rad_per_m) {
  const double sin_i = std::sin(station.inclination_rad);
  const double cos_i = std::cos(station.inclination_rad);
  const double sin_am = std::sin(station.magnetic_azimuth_rad);
  const double cos_am = std::cos(station.magnetic_azimuth_rad);
  const double sin_at = std::sin(station.true_azimuth_rad);
  const double cos_at = std::cos(station.true_azimuth_rad);
  const double tan_dip = std::tan(well.dip_rad);
  const double g = well.gravity_m_s2;
  const double b_horizontal = well.b_total_nT * std::cos(well.dip_rad);
  const double root2 = std::numbers::sqrt2;

  // {dMD/de, dI/de, sin(I) dA/de}
  switch (function) {
    case WeightingFunction::kDref:
      return {1.0, 0.0, 0.0};
    case WeightingFunction::kDsf:
      return {station.md_m, 0.0, 0.0};
    case WeightingFunction::kDst:
      return {station.md_m * station.tvd_m, 0.0, 0.0};
    case WeightingFunction::kAbxyTi1:
      return {0.0, -cos_i / g, sin_i * tan_dip * cos_i * sin_am / g};
    case WeightingFunction::kAbxyTi2:
      // dA/de = (cot I - tan(dip) cos AzM) / G
      return {0.0, 0.0, (cos_i - sin_i * tan_dip * cos_am) / g};
    case WeightingFunction::kAbz:
      return {0.0, -sin_i / g, sin_i * tan_dip * sin_i * sin_am / g};
    case WeightingFunction::kAsxyTi1:
      return {0.0, sin_i * cos_i / root2, -sin_i * tan_dip * sin_i * cos_i * sin_am / root2};
    case WeightingFunction::kAsxyTi2:
      return {0.0, sin_i * cos_i / 2.0, -sin_i * tan_dip * sin_i * cos_i * sin_am / 2.0};
    case WeightingFunction::kAsxyTi3:
      return {0.0, 0.0, sin_i * (tan_dip * sin_i * cos_am - cos_i) / 2.0};
    case WeightingFunction::kAsz:
      return {0.0, -sin_i * cos_i, sin_i * tan_dip * sin_i * cos_i * sin_am};
    case WeightingFunction::kMbxyTi1:
      return {0.0, 0.0, -sin_i * cos_i * sin_am / b_horizontal};
    case WeightingFunction::kMbxyTi2:
      return {0.0, 0.0, sin_i * cos_am / b_horizontal};
    case WeightingFunction::kMbz:
    case WeightingFunction::kAmil:
      return {0.0, 0.0, -sin_i * sin_i * sin_am / b_horizontal};
    case WeightingFunction::kMsxyTi1:
      return {0.0, 0.0, sin_i * sin_i * sin_am * (tan_dip * cos_i + sin_i * cos_am) / root2};
    case WeightingFunction::kMsxyTi2:
      return {0.0, 0.0,
              sin_i * sin_am * (tan_dip * sin_i * cos_i - cos_i * cos_i * cos_am - cos_am) / 2.0};
    case WeightingFunction::kMsxyTi3:
      return {0.0, 0.0,
              sin_i *
                  (cos_i * cos_am * cos_am - cos_i * sin_am * sin_am - tan_dip * sin_i * cos_am) /
                  2.0};
    case WeightingFunction::kMsz:
      return {0.0, 0.0, -sin_i * (sin_i * cos_am + tan_dip * cos_i) * sin_i * sin_am};
    case WeightingFunction::kAzimuth:
      return {0.0, 0.0, sin_i};
    case WeightingFunction::kDbh:
      return {0.0, 0.0, sin_i / b_horizontal};
    case WeightingFunction::kSag:
      return {0.0, sin_i, 0.0};
    case WeightingFunction::kSage:
      return {0.0, std::pow(std::max(sin_i, 0.0), 0.25), 0.0};
    case WeightingFunction::kXym1:
      return {0.0, std::abs(sin_i), 0.0};
    case WeightingFunction::kXym2:
      return {0.0, 0.0, -sin_i};
    case WeightingFunction::kXym3:
      // dA/de = -|cos I| sin AzT / sin I
      return {0.0, std::abs(cos_i) * cos_at, -std::abs(cos_i) * sin_at};
    case WeightingFunction::kXym4:
      // dA/de = |cos I| cos AzT / sin I
      return {0.0, std::abs(cos_i) * sin_at, std::abs(cos_i) * cos_at};
    case WeightingFunction::kXym3e: {
      const double factor = short_interval_factor(station);
      return {0.0, factor * std::abs(cos_i) * cos_at, -factor * std::abs(cos_i) * sin_at};
    }
    case WeightingFunction::kXym4e: {
      const double factor = short_interval_factor(station);
      return {0.0, factor * std::abs(cos_i) * sin_at, factor * std::abs(cos_i) * cos_at};
    }
    case WeightingFunction::kXcla:
      // dA/de = max(sin|dAzT|, tortuosity dMD / sin I), over the whole leg before the station
      return {0.0, 0.0, unseen_azimuthal_turn(station, well, tortuosity_rad_per_m)};
    case WeightingFunction::kXclh: {
      const double interval_m = station.md_m - station.previous_md_m;
      return {0.0,
              std::max(std::abs(station.inclination_rad - station.previous_inclination_rad),
                       tortuosity_rad_per_m * interval_m),
              0.0};
    }
    case WeightingFunction::kAxyzMis:
      return {0.0, 1.0, 0.0};
    case WeightingFunction::kAxyzSf:
      return {0.0, 1.3 * sin_i * cos_i, 0.0};
    case WeightingFunction::kAxyzZb:
      return {0.0, sin_i / g, 0.0};
    case WeightingFunction::kGxyB1:
    case WeightingFunction::kGxyB2:
    case WeightingFunction::kGxyG1:
    case WeightingFunction::kGxyG4:
    case WeightingFunction::kGxyRn:
      return {0.0, 0.0, sin_i * gyrocompass_azimuth_weight_s(function, station, well)};
  }
  return {};
}

}  // namespace stochnav::survey_error

#include "stochnav/survey_error/survey_inputs.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string_view>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/io/csv_table_reader.hpp"
#include "stochnav/io/json_document.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/plugin/params.hpp"

namespace stochnav::survey_error {
namespace {

using plugin::Bound;
using plugin::ParamReader;

/// A value's allowed interval, for messages: "[0, 360)".
struct Interval {
  double low;
  double high;
  bool low_open;
  bool high_open;

  bool contains(double value) const {
    return (low_open ? value > low : value >= low) && (high_open ? value < high : value <= high);
  }
  std::string text() const {
    return fmt::format("{}{:g}, {:g}{}", low_open ? '(' : '[', low, high, high_open ? ')' : ']');
  }
};

constexpr Interval kInclinationDeg{0.0, 180.0, false, false};
constexpr Interval kAzimuthDeg{0.0, 360.0, false, true};

/// A required number within `interval`; ConfigError "<pointer>: found V; expected a number in
/// [a, b] (unit)" otherwise.
double number_within(ParamReader& reader, std::string_view key, Interval interval,
                     std::string_view unit) {
  const std::string expected = "a number in " + interval.text() + " (" + std::string(unit) + ")";
  const nlohmann::json& value = reader.required(key, expected);
  if (!value.is_number() || !interval.contains(value.get<double>())) {
    throw ConfigError(reader.pointer(key) + ": found " + value.dump() + "; expected " + expected);
  }
  return value.get<double>();
}

}  // namespace

std::vector<ListingStation> read_survey_listing(const std::string& path) {
  constexpr std::array<std::string_view, 3> kColumns = {"md_m", "inclination_deg", "azimuth_deg"};
  CsvTableReader reader(path, kColumns);
  std::vector<ListingStation> stations;
  std::array<double, 3> row{};
  const bool typed_rows = reader.has_column("station_type");
  while (reader.next(row)) {
    // A run's survey.csv: its tie-on row (at the depth of its first station, taken at rest at
    // the tie-on) and its projection to the bit are not survey stations.
    if (typed_rows) {
      const std::string type = reader.text_cell("station_type");
      if (type == "tie_on" || type == "projection_to_bit") continue;
    }
    const auto where = [&] { return path + ":" + std::to_string(reader.line_number()) + ": "; };
    const auto [md_m, inclination_deg, azimuth_deg] = row;
    if (!stations.empty() && !(md_m > stations.back().md_m)) {
      throw InputError(where() +
                       fmt::format("md_m {:g} does not increase (previous station {:g} m); "
                                   "list the stations once each, in order of depth",
                                   md_m, stations.back().md_m));
    }
    if (!kInclinationDeg.contains(inclination_deg)) {
      throw InputError(where() + fmt::format("inclination_deg {:g} is outside {}; give the "
                                             "inclination from vertical in degrees",
                                             inclination_deg, kInclinationDeg.text()));
    }
    if (!kAzimuthDeg.contains(azimuth_deg)) {
      throw InputError(where() + fmt::format("azimuth_deg {:g} is outside {}; give the azimuth "
                                             "in degrees, wrapped into {}",
                                             azimuth_deg, kAzimuthDeg.text(), kAzimuthDeg.text()));
    }
    stations.push_back({md_m, inclination_deg * kRadPerDeg, azimuth_deg * kRadPerDeg});
  }
  if (stations.size() < 2) {
    throw InputError(path + fmt::format(": {} station(s); the error model needs at least two "
                                        "(the tie-on and one survey station)",
                                        stations.size()));
  }
  return stations;
}

WellParameters well_parameters_from_json(const nlohmann::json& json) {
  ParamReader reader(json, "");
  WellParameters well;
  well.latitude_rad =
      number_within(reader, "latitude_deg", {-90.0, 90.0, false, false}, "deg") * kRadPerDeg;
  well.b_total_nT = reader.number("b_total_nT", Bound::kPositive, "nT");
  well.dip_rad = number_within(reader, "dip_deg", {-90.0, 90.0, true, true}, "deg") * kRadPerDeg;
  well.declination_rad =
      number_within(reader, "declination_deg", {-180.0, 180.0, false, false}, "deg") * kRadPerDeg;
  well.convergence_rad =
      number_within(reader, "convergence_deg", {-180.0, 180.0, false, false}, "deg") * kRadPerDeg;
  well.gravity_m_s2 = reader.number("gravity_m_s2", Bound::kPositive, "m/s^2");
  well.earth_rate_rad_s =
      reader.number("earth_rate_deg_h", Bound::kNonNegative, "deg/h") * kRadPerDeg / 3600.0;
  well.vertical_section_azimuth_rad =
      number_within(reader, "vertical_section_azimuth_deg", kAzimuthDeg, "deg") * kRadPerDeg;
  well.vertical_inc_limit_rad =
      number_within(reader, "vertical_inc_limit_deg", {0.0, 90.0, false, true}, "deg") * kRadPerDeg;
  const std::string references = "\"true\" or \"grid\"";
  const nlohmann::json& reference = reader.required("azimuth_reference", references);
  if (reference == "true") {
    well.azimuth_reference = AzimuthReference::kTrue;
  } else if (reference == "grid") {
    well.azimuth_reference = AzimuthReference::kGrid;
  } else {
    throw ConfigError(reader.pointer("azimuth_reference") + ": found " + reference.dump() +
                      "; expected " + references);
  }
  if (reader.has("tie_on_tvd_m"))
    well.tie_on_tvd_m = reader.number("tie_on_tvd_m", Bound::kAny, "m");
  reader.finish();
  return well;
}

WellParameters read_well_parameters(const std::string& path) {
  const nlohmann::json json = read_json_document(path, "the well file (--well)");
  try {
    return well_parameters_from_json(json);
  } catch (const ConfigError& error) {
    throw ConfigError(path + ": " + error.what());
  }
}

void check_listing_against_well(const std::vector<ListingStation>& stations,
                                const WellParameters& well, const std::string& well_path,
                                const std::string& listing_path) {
  if (stations.empty() || stations.front().md_m == 0.0 || well.tie_on_tvd_m) return;
  throw ConfigError(fmt::format(
      "{}: /tie_on_tvd_m: missing, and {} starts at MD {:g} m, not at the surface; add "
      "\"tie_on_tvd_m\": the TVD (m) of its first station, for the depth-stretch term DSTG",
      well_path, listing_path, stations.front().md_m));
}

void check_well_for_gyro(const WellParameters& well, const std::string& well_path) {
  if (!(well.earth_rate_rad_s > 0.0)) {
    throw ConfigError(well_path +
                      ": /earth_rate_deg_h: 0; the gyro model gyrocompasses, so give the Earth "
                      "rate (> 0, e.g. 15.041 deg/h)");
  }
  if (!(std::abs(well.latitude_rad) < std::numbers::pi / 2.0)) {
    throw ConfigError(fmt::format(
        "{}: /latitude_deg: {:g}; a gyrocompass cannot find north at a pole: the gyro model "
        "needs a latitude in (-90, 90) deg",
        well_path, well.latitude_rad * kDegPerRad));
  }
}

NoiseModel read_gyro_noise_model(const std::string& path) {
  const nlohmann::json json = read_json_document(path, "the gyro noise model (--noise-model)");
  NoiseModel model;
  try {
    model = noise_model_from_json(json);
  } catch (const ConfigError& error) {
    throw ConfigError(path + ": " + error.what());
  }
  if (quantity_of(model.unit) != Quantity::kAngularRate) {
    throw ConfigError(fmt::format(
        "{}: /units: found \"{}\"; expected a gyro rate unit (deg/h, deg/s or rad/s): give the "
        "fitted noise model of the tool's x-y gyros",
        path, unit_name(model.unit)));
  }
  return model;
}

}  // namespace stochnav::survey_error

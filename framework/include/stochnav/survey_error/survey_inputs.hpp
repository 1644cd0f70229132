#pragma once
// Reading the inputs of `stochnav survey`: a survey listing (CSV) and the well's parameters
// (JSON). Every problem is one line naming the file and line, or the JSON pointer, and the fix:
// InputError for the listing, ConfigError for the well file.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stochnav/model/noise_model.hpp"
#include "stochnav/survey_error/error_propagation.hpp"
#include "stochnav/survey_error/well_parameters.hpp"

namespace stochnav::survey_error {

/// A listing CSV: a header row with the columns md_m, inclination_deg, azimuth_deg (in any
/// order; other columns are allowed and ignored, so a full field listing can be given as it
/// is), then one row per station, the tie-on first. Blank lines and '#' lines are skipped.
/// Requires at least two stations, MD strictly increasing, inclination in [0, 180] deg,
/// azimuth in [0, 360) deg, no NaN. Returns radians.
/// Rows whose column station_type is a `stochnav run` survey.csv's "tie_on" or
/// "projection_to_bit" are skipped: the first survey station is the error model's tie-on, as
/// in a listing without them (the run's tie-on row sits at the depth of its first station,
/// taken at rest there). Other station_type values are read like any row.
std::vector<ListingStation> read_survey_listing(const std::string& path);

/// The well's parameters from a JSON object with exactly these keys (angles in degrees):
///   latitude_deg [-90, 90], b_total_nT > 0, dip_deg (-90, 90), declination_deg [-180, 180],
///   convergence_deg [-180, 180], gravity_m_s2 > 0, earth_rate_deg_h >= 0,
///   vertical_section_azimuth_deg [0, 360), vertical_inc_limit_deg [0, 90),
///   azimuth_reference "true" | "grid",
/// and optionally tie_on_tvd_m (m, the first station's TVD; needed when the listing does not
/// start at MD 0). Unknown keys, missing keys and wrong types throw ConfigError
/// "/<key>: problem; expected form".
WellParameters well_parameters_from_json(const nlohmann::json& json);

/// read_json_document + well_parameters_from_json, the messages prefixed with `path`.
WellParameters read_well_parameters(const std::string& path);

/// Throws ConfigError when the listing needs what the well file lacks: tie_on_tvd_m when the
/// first station's MD is not 0. `well_path` and `listing_path` name the files in the message.
void check_listing_against_well(const std::vector<ListingStation>& stations,
                                const WellParameters& well, const std::string& well_path,
                                const std::string& listing_path);

/// Throws ConfigError when the well cannot carry a gyrocompass model (gyro_ns_ct): an Earth
/// rate of 0 ("/earth_rate_deg_h") or a latitude of +-90 deg ("/latitude_deg"), naming
/// `well_path` (a file, or a run config's JSON pointer to its "well").
void check_well_for_gyro(const WellParameters& well, const std::string& well_path);

/// A fitted noise model of the x-y gyros (the JSON of `stochnav fit`, model/noise_model_json.hpp)
/// from `path`: InputError when it cannot be read or is not JSON, ConfigError "<path>:
/// <pointer>: problem" when it is not a valid noise model or not in a gyro rate unit.
NoiseModel read_gyro_noise_model(const std::string& path);

}  // namespace stochnav::survey_error

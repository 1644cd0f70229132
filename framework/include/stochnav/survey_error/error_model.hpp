#pragma once
// The ISCWSA MWD survey error models as data: each error source's code, weighting function,
// magnitude (with its unit as the ISCWSA tables give it) and propagation mode. The tables
// themselves are in src/survey_error/mwd_models.cpp (and the OWSG gyro tool model's in
// gyro_models.cpp), one row per source; docs/survey-error-model.md lists them for readers.
//
// Propagation modes (ISCWSA MWD Rev5 document, after Williamson, SPE 67616): an error source is
//   random (R)      independent from station to station: the covariances of the stations add;
//   systematic (S)  the same at every station of one survey leg (run): the error vectors add;
//   per-well (W)    the same for all stations of one well;
//   global (G)      the same for all wells of a field.
// Within one well S, W and G all correlate every station with every other one, so the position
// covariance of a single well treats them alike; they differ only between wells (clearance).
// A listing here is one survey leg, as in the ISCWSA example wells.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace stochnav::survey_error {

enum class PropagationMode { kRandom, kSystematic, kPerWell, kGlobal };

/// "R", "S", "W" or "G", as the ISCWSA tables write the mode.
std::string_view propagation_mode_letter(PropagationMode mode);

/// The ISCWSA weighting functions: how an error source changes the measured depth,
/// inclination and azimuth of a station (survey_error/weighting_functions.hpp gives each one).
/// Names follow the ISCWSA function names (ABXY-TI1 -> kAbxyTi1).
enum class WeightingFunction {
  kDref,     ///< depth reference: MD + 1
  kDsf,      ///< depth scale factor: MD + MD
  kDst,      ///< depth stretch: MD + MD * TVD
  kAbxyTi1,  ///< accelerometer bias, x-y, tool-face independent term 1
  kAbxyTi2,  ///< accelerometer bias, x-y, term 2 (cot I: has a near-vertical form)
  kAbz,      ///< accelerometer bias, z
  kAsxyTi1,  ///< accelerometer scale factor, x-y, terms 1-3
  kAsxyTi2,
  kAsxyTi3,
  kAsz,      ///< accelerometer scale factor, z
  kMbxyTi1,  ///< magnetometer bias, x-y, terms 1-2
  kMbxyTi2,
  kMbz,      ///< magnetometer bias, z
  kMsxyTi1,  ///< magnetometer scale factor, x-y, terms 1-3
  kMsxyTi2,
  kMsxyTi3,
  kMsz,      ///< magnetometer scale factor, z
  kAzimuth,  ///< an azimuth error (declination terms): A + 1
  kDbh,   ///< an error of the horizontal field (B cos dip) times declination: A + 1 / (B cos dip)
  kAmil,  ///< axial magnetic interference
  kSag,   ///< BHA sag (Rev4): I + sin I
  kSage,  ///< BHA sag, enhanced (Rev5): I + sin(I)^(1/4)
  kXym1,  ///< x-y misalignment terms 1-4 (3 and 4 have near-vertical forms)
  kXym2,
  kXym3,
  kXym4,
  kXym3e,  ///< XYM3 and XYM4 as random terms scaled for short survey intervals (Rev5)
  kXym4e,
  kXcla,  ///< tortuosity between stations, azimuthal (whole leg before the station)
  kXclh,  ///< tortuosity between stations, high-side (whole leg before the station)
  // The OWSG gyro tool models (GYRO-NS-CT, GYRO-NS, GYRO-MWD; after Torkildsen et al., SPE
  // 90408):
  kAxyzMis,  ///< xyz accelerometer misalignment: I + 1
  kAxyzSf,   ///< xyz accelerometer scale factor: I + 1.3 sin I cos I
  kAxyzZb,   ///< z accelerometer bias: I + sin I / G
  /// x-y gyro biases, g-dependent errors and rate noise of a stationary gyrocompass
  /// (is_gyrocompass_weighting: carried from the initialising station into a continuous survey)
  kGxyB1,  ///< A + sin AzT / (Omega cos(lat) cos I)
  kGxyB2,  ///< A + cos AzT / (Omega cos(lat))
  kGxyG1,  ///< A + cos AzT sin I / (Omega cos(lat))
  kGxyG4,  ///< A + sin AzT tan I / (Omega cos(lat))
  /// A + NRF sqrt(1 - cos^2 AzT sin^2 I) / (Omega cos(lat) cos I), NRF the model's
  /// SurveyErrorModel::noise_reduction_factor (GXY-RN of GYRO-NS and GYRO-MWD; GYRO-NS-CT's
  /// GXY-RN is continuous_gyro.hpp's)
  kGxyRn,
};

/// The unit an ISCWSA table gives a magnitude in.
enum class MagnitudeUnit {
  kMetre,            ///< m
  kPerMetre,         ///< 1/m
  kMetrePerSecond2,  ///< m/s^2
  kNanotesla,        ///< nT
  kDimensionless,    ///< -
  kDegree,           ///< deg (rad internally)
  kDegreeNanotesla,  ///< deg.nT (rad.nT internally)
  kDegreePerHour,    ///< deg/h (rad/s internally): gyro rate errors
};

/// "m", "1/m", "m/s2", "nT", "-", "deg", "deg.nT", "deg/h".
std::string_view magnitude_unit_name(MagnitudeUnit unit);

/// One error source of a model.
struct ErrorSource {
  std::string code;  ///< the ISCWSA code ("ABXY-TI1S", "DEC-U", ...)
  WeightingFunction weighting;
  double magnitude = 0.0;  ///< 1-sigma, in `unit`
  MagnitudeUnit unit = MagnitudeUnit::kDimensionless;
  PropagationMode mode = PropagationMode::kSystematic;

  /// The magnitude in the units the weighting functions take: m, 1/m, m/s^2, nT, rad, rad.nT,
  /// rad/s.
  double magnitude_si() const;
};

/// An error model: its sources in the ISCWSA example workbook's order, and the conventions of
/// the revision.
struct SurveyErrorModel {
  std::string name;   ///< "mwd_rev5", "mwd_rev4"
  std::string title;  ///< "ISCWSA MWD Rev5.11", ...
  std::vector<ErrorSource> sources;
  /// XCLA / XCLH: the tortuosity assumed between stations when the survey shows less
  /// (rad/m; the ISCWSA default 1 deg / 100 ft).
  double default_tortuosity_rad_per_m = 0.0;
  /// The Rev5 workbook's convention for the first leg (tie-on to first station): the tie-on's
  /// direction is the first station's, so the first station's inclination and azimuth errors
  /// turn the whole first leg, not half of it. Rev4: false (half, as at every station).
  bool first_station_turns_whole_first_leg = false;
  /// Gyro tool models with a continuous survey (GYRO-NS-CT): below this inclination (rad) every
  /// station is a stationary gyrocompass; the first station at or above it (after the tie-on)
  /// initialises the continuous survey (continuous_gyro.hpp, continuous_initialisation_station),
  /// and the gyrocompass terms (is_gyrocompass_weighting) keep that station's azimuth error at
  /// every later station: the continuous survey carries its initial azimuth forward. Absent:
  /// every station is evaluated with its own weights.
  std::optional<double> continuous_start_inclination_rad;
  /// kGxyRn: the tool's noise reduction factor (the reduction of the rate noise by combining
  /// the measurements of one gyrocompass station; OWSG: 1 unless the tool model gives one).
  double noise_reduction_factor = 1.0;
};

/// The model called `name` ("mwd_rev5" = ISCWSA MWD Rev5.11, 35 sources; "mwd_rev4", 27
/// sources). Throws ConfigError "--model 'NAME': unknown survey error model; use ..." (with a
/// "did you mean" for a likely typo; tool_models.hpp), or "not an ISCWSA MWD model" for the
/// OWSG gyro tool models (tool_models.hpp: gyro_ns_ct, a table plus terms no propagation mode
/// describes, continuous_gyro.hpp; gyro_ns and gyro_mwd, gyro_ns_model and gyro_mwd_model).
const SurveyErrorModel& survey_error_model(std::string_view name);

/// The names survey_error_model() knows, in a stable order.
std::span<const std::string> survey_error_model_names();

}  // namespace stochnav::survey_error

#pragma once
// Configuration of an MWD scenario (`stochnav simulate scenario`), as plain structs in SI units
// (angles in rad, times in s, accelerations in m/s^2). The JSON form and its validation live in
// scenario/scenario_config_json.hpp; see configs/scenarios/*.json for documented examples.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/model/noise_model.hpp"

namespace stochnav {

enum class ScenarioKind { kVibrationTable, kDrilling };
enum class ImuOutput { kIncrements, kRates };

struct ImuOutputConfig {
  double rate_hz = 100.0;                     ///< IMU epoch rate (Hz), in [100, 1000]
  ImuOutput output = ImuOutput::kIncrements;  ///< imu.csv: increments (rad, m/s) or rates
  double truth_rate_hz = 0.0;                 ///< truth.csv rate (Hz); 0: the IMU rate
  double aid_rate_hz = 1.0;                   ///< aids.csv rate (Hz)
};

struct SiteConfig {
  double latitude_rad = 0.0;   ///< geodetic latitude of the table / wellhead (rad)
  double longitude_rad = 0.0;  ///< longitude (rad)
  double height_m = 0.0;       ///< ellipsoidal height of the table / rig floor (m)
};

/// Errors of one sensor triad (gyros or accelerometers). Natural units: rad/s for gyros, m/s^2
/// for accelerometers.
struct SensorErrorConfig {
  /// Noise on every axis throughout the run (per axis x, y, z; the same model may repeat).
  std::array<NoiseModel, 3> noise;
  /// Noise scaled per phase by the phase's noise scale (the vibration-sensitive part); terms may
  /// be empty. Its coefficients multiply by the scale, so a scale s multiplies its variance by s^2.
  std::array<NoiseModel, 3> scheduled_noise;
  std::array<double, 3> constant_bias{};  ///< rad/s or m/s^2
  double turn_on_bias_sigma = 0.0;        ///< per run, per axis, 1-sigma; rad/s or m/s^2
  std::array<double, 3> scale_factor{};   ///< dimensionless (1e-6 = 1 ppm)
};

/// Random vibration from a PSD table: a sum of sinusoids (see scenario/vibration.hpp).
struct RandomVibrationConfig {
  std::vector<std::array<double, 2>> psd;  ///< (frequency Hz, PSD (m/s^2)^2/Hz), ascending
  double rms_mps2 = 0.0;                   ///< total RMS the sum is scaled to (m/s^2)
  int components = 128;                    ///< number of sinusoids
};

struct SineVibrationConfig {
  double frequency_hz = 0.0;    ///< Hz
  double amplitude_mps2 = 0.0;  ///< peak acceleration along X (m/s^2)
};

enum class TableMotion { kStatic, kSine, kRandom };

struct TablePhaseConfig {
  std::string name;
  double duration_s = 0.0;
  TableMotion motion = TableMotion::kStatic;
  SineVibrationConfig sine;
  RandomVibrationConfig random;
  double gyro_noise_scale = 1.0;   ///< factor on the scheduled gyro noise
  double accel_noise_scale = 1.0;  ///< factor on the scheduled accelerometer noise
};

struct VibrationTableConfig {
  MwdAttitude attitude;                  ///< fixed tool attitude
  std::vector<TablePhaseConfig> phases;  ///< in time order
};

/// One section of a general well path: inclination and azimuth change linearly with measured
/// depth (constant build and turn rates; both zero: a straight hold).
struct WellSectionConfig {
  double length_m = 0.0;              ///< measured-depth length of the section (m), > 0
  double build_rate_rad_per_m = 0.0;  ///< dI/dmd (rad/m), any sign (negative: drop)
  double turn_rate_rad_per_m = 0.0;   ///< dA/dmd (rad/m), any sign (positive: clockwise)
};

/// The well path, measured depth 0 at the wellhead. Two forms:
/// - plane (sections empty): vertical to kickoff_md_m, a build at build_rate_rad_per_m (turning
///   at turn_rate_rad_per_m, default 0 = in the plane of azimuth_rad) to target_inclination_rad,
///   then a straight hold;
/// - sections: from start_inclination_rad / start_azimuth_rad at md 0, the sections in order,
///   then a straight hold beyond the last one. Inclination stays in [0, pi] (validated).
/// The azimuth is a parameter of the path, defined also where the path is vertical: it fixes
/// the high side there (the convention of ins/mwd_attitude.hpp's construction).
struct WellPathConfig {
  double kickoff_md_m = 0.0;            ///< measured depth where the build starts (m)
  double build_rate_rad_per_m = 0.0;    ///< inclination gain per metre in the build (rad/m), > 0
  double target_inclination_rad = 0.0;  ///< hold inclination (rad), (0, pi/2]
  double azimuth_rad = 0.0;             ///< azimuth of the well plane (rad)
  double turn_rate_rad_per_m = 0.0;     ///< azimuth change per metre in the build (rad/m)
  std::vector<WellSectionConfig> sections;  ///< non-empty: the sections form
  double start_inclination_rad = 0.0;       ///< sections form: inclination at md 0 (rad)
  double start_azimuth_rad = 0.0;           ///< sections form: azimuth at md 0 (rad)
};

struct VibrationEpisodeConfig {
  double start_s = 0.0;               ///< s
  double end_s = 0.0;                 ///< s, > start_s
  double axial_amplitude_mps2 = 0.0;  ///< peak axial acceleration (m/s^2)
  double frequency_hz = 0.0;          ///< axial vibration frequency (Hz)
};

/// Axial vibration tied to the drilled depth: active only while the tool drills (measured depth
/// advancing; never in connections or orientation pauses) with its depth in [start_md_m,
/// end_md_m); each such time span gets the raised-cosine envelope of a time episode.
struct MdVibrationEpisodeConfig {
  double start_md_m = 0.0;            ///< m
  double end_md_m = 0.0;              ///< m, > start_md_m
  double axial_amplitude_mps2 = 0.0;  ///< peak axial acceleration (m/s^2)
  double frequency_hz = 0.0;          ///< axial vibration frequency (Hz)
};

enum class DrillMode { kRotate, kSlide };

/// One segment of the per-stand drilling pattern.
struct StandSegmentConfig {
  DrillMode mode = DrillMode::kRotate;
  double length_m = 0.0;        ///< measured depth drilled (m), > 0
  double rop_mps = 0.0;         ///< rate of penetration (m/s), > 0
  double rotation_radps = 0.0;  ///< rotate: toolface rotation rate (rad/s); slide: 0
  double toolface_rad = 0.0;    ///< slide: the toolface held (rad); rotate: unused
};

struct NoiseScales {
  double gyro = 1.0;
  double accel = 1.0;
};

struct DrillingConfig {
  WellPathConfig well;
  double start_md_m = 0.0;        ///< measured depth of the tool at t = 0 (m)
  double duration_s = 0.0;        ///< scenario length (s)
  double initial_static_s = 0.0;  ///< stationary alignment period at the start (s)
  double rop_mps = 0.0;           ///< rate of penetration while drilling (m/s)
  double rotation_radps = 0.0;    ///< toolface rotation rate while drilling (rad/s), 0 = slide
  double initial_toolface_rad = 0.0;
  double stand_length_m = 0.0;  ///< MD drilled between connections (m)
  double connection_s = 0.0;    ///< stationary time of a pipe connection (s)
  double ramp_s = 0.0;          ///< raised-cosine ramp of ROP and rotation (s)
  std::vector<VibrationEpisodeConfig> vibration_episodes;  ///< ascending, non-overlapping
  /// Episodes by measured depth; ascending, non-overlapping among themselves.
  std::vector<MdVibrationEpisodeConfig> md_vibration_episodes;
  /// Each stand drills these segments in order (lengths sum to stand_length_m). Empty: one
  /// segment per stand at rop_mps and rotation_radps, without orientation pause.
  std::vector<StandSegmentConfig> stand_pattern;
  /// Before each slide segment the tool stands still in depth while the toolface turns to the
  /// slide toolface (shortest way) with a raised-cosine profile over orient_s (s), > 0.
  double orient_s = 30.0;
  NoiseScales static_noise;     ///< scheduled-noise scales when stationary
  NoiseScales drilling_noise;   ///< when drilling without a vibration episode
  NoiseScales vibration_noise;  ///< during vibration episodes
};

struct AidConfig {
  double depth_scale_error = 0.0;  ///< relative error of the pipe tally (dimensionless)
  double depth_noise_m = 0.0;      ///< white error of each depth reading (m, 1-sigma)
  double rop_noise_mps = 0.0;      ///< white error of each ROP reading (m/s, 1-sigma)
  /// aids.csv time = the sample's true time + clock_offset_s (s), |x| < 1: a rig clock off the
  /// IMU's; samples are still taken on the aid_rate_hz grid of true time.
  double clock_offset_s = 0.0;
  double latency_s = 0.0;  ///< the readings written at true time t are those of t - latency_s (s)
  /// True-time spans [start, end] (s) without aids.csv rows; ascending, not overlapping.
  std::vector<std::array<double, 2>> dropouts;
};

struct ScenarioConfig {
  std::string description;
  ScenarioKind kind = ScenarioKind::kVibrationTable;
  std::uint64_t seed = 0;
  ImuOutputConfig imu;
  SiteConfig site;
  SensorErrorConfig gyro;
  SensorErrorConfig accel;
  AidConfig aids;
  std::optional<VibrationTableConfig> vibration_table;  ///< kind == kVibrationTable
  std::optional<DrillingConfig> drilling;               ///< kind == kDrilling
  /// "noise_variance_scale": factors on the VARIANCE of the scheduled noise (its amplitude
  /// scales by the square root), on top of the phase scales; 1 = as configured.
  NoiseScales noise_variance_scale;
  /// "moving_noise_variance_scale": the same, only in phases in which the tool moves
  /// (vibration-table vibration, drilling); the two multiply where both apply.
  NoiseScales moving_noise_variance_scale;
};

/// Total scenario length (s): the sum of the table phases, or drilling.duration_s.
double scenario_duration_s(const ScenarioConfig& config);

}  // namespace stochnav

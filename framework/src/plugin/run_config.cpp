#include "stochnav/plugin/run_config.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/io/json_document.hpp"
#include "stochnav/plugin/params.hpp"
#include "stochnav/survey_error/survey_inputs.hpp"
#include "stochnav/survey_error/tool_models.hpp"

namespace stochnav::plugin {
namespace fs = std::filesystem;
namespace {

fs::path resolve(const fs::path& config_dir, const std::string& text) {
  const fs::path path(text);
  return path.is_absolute() ? path : config_dir / path;
}

fs::path existing_file(ParamReader& reader, std::string_view key, const fs::path& config_dir) {
  const fs::path path = resolve(config_dir, reader.text(key));
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    throw ConfigError(reader.pointer(key) + ": file not found: " + path.string() +
                      "; give an existing file (relative paths start at the config's folder)");
  }
  return path;
}

const nlohmann::json& object_at(ParamReader& reader, std::string_view key, bool required) {
  const nlohmann::json& value = reader.raw(key);
  if (value.is_null() && !required) return value;
  if (!value.is_object()) {
    throw ConfigError(reader.pointer(key) + (value.is_null() ? ": missing" : ": not an object") +
                      "; expected an object");
  }
  return value;
}

DataConfig parse_data(const nlohmann::json& json, const std::string& pointer,
                      const fs::path& config_dir) {
  ParamReader reader(json, pointer);
  DataConfig data;
  const bool scenario = reader.has("scenario");
  const bool imu = reader.has("imu");
  if (scenario == imu) {
    throw ConfigError(
        pointer + ": " +
        (scenario ? std::string("both \"scenario\" and \"imu\" given") : std::string("no data")) +
        "; expected {\"scenario\": FOLDER} or {\"imu\": FILE, \"truth\": FILE, "
        "\"aids\": FILE}");
  }
  if (scenario) {
    data.scenario_dir = resolve(config_dir, reader.text("scenario"));
    std::error_code error;
    if (!fs::is_directory(data.scenario_dir, error)) {
      throw ConfigError(reader.pointer("scenario") +
                        ": folder not found: " + data.scenario_dir.string() +
                        "; give the folder written by `stochnav simulate scenario`");
    }
    data.imu = data.scenario_dir / kScenarioImuFile;
    if (!fs::is_regular_file(data.imu, error)) {
      throw ConfigError(reader.pointer("scenario") + ": no " + std::string(kScenarioImuFile) +
                        " in " + data.scenario_dir.string() +
                        "; give the folder written by `stochnav simulate scenario`");
    }
    if (fs::is_regular_file(data.scenario_dir / kScenarioTruthFile, error)) {
      data.truth = data.scenario_dir / kScenarioTruthFile;
    }
    if (fs::is_regular_file(data.scenario_dir / kScenarioAidsFile, error)) {
      data.aids = data.scenario_dir / kScenarioAidsFile;
    }
  } else {
    data.imu = existing_file(reader, "imu", config_dir);
    if (reader.has("truth")) data.truth = existing_file(reader, "truth", config_dir);
    if (reader.has("aids")) data.aids = existing_file(reader, "aids", config_dir);
  }
  reader.finish();
  return data;
}

PluginConfig parse_plugin_entry(ParamReader& reader, const std::string& pointer) {
  PluginConfig entry;
  entry.pointer = pointer;
  entry.type = reader.text("plugin");
  const nlohmann::json& params = reader.raw("params");
  if (!params.is_null()) {
    if (!params.is_object()) {
      throw ConfigError(reader.pointer("params") +
                        ": not an object; expected the plugin's "
                        "parameters as an object");
    }
    entry.params = params;
  }
  return entry;
}

FitConfig parse_fit(const nlohmann::json& json, const std::string& pointer, SensorGroup group,
                    const fs::path& config_dir, const fs::path& default_record) {
  ParamReader reader(json, pointer);
  FitConfig fit;
  fit.record = reader.has("record") ? existing_file(reader, "record", config_dir) : default_record;
  fit.start_s = reader.number_or("start_s", 0.0, Bound::kNonNegative, "s");
  if (reader.has("end_s")) {
    fit.end_s = reader.number("end_s", Bound::kPositive, "s");
    if (!(*fit.end_s > fit.start_s)) {
      throw ConfigError(reader.pointer("end_s") + ": " + std::to_string(*fit.end_s) +
                        " s is not after start_s; expected end_s > start_s");
    }
  }
  const auto& defaults = group == SensorGroup::kGyro ? kGyroColumns : kAccelColumns;
  for (std::size_t i = 0; i < 3; ++i) fit.columns[i] = std::string(defaults[i]);
  const nlohmann::json& columns = reader.raw("columns");
  if (!columns.is_null()) {
    const bool ok = columns.is_array() && columns.size() == 3 &&
                    std::all_of(columns.begin(), columns.end(), [](const nlohmann::json& c) {
                      return c.is_string() && !c.get<std::string>().empty();
                    });
    if (!ok) {
      throw ConfigError(reader.pointer("columns") + ": found " + columns.dump() +
                        "; expected three column names [x, y, z]");
    }
    for (std::size_t i = 0; i < 3; ++i) fit.columns[i] = columns[i].get<std::string>();
  }
  reader.finish();
  return fit;
}

constexpr double kDegPerHourPerRadPerSecond = kDegPerRad * 3600.0;
constexpr double kPpm = 1e-6;

using Vector3 = Eigen::Vector3d;
std::array<double, 3> array_of(const Vector3& v) { return {v.x(), v.y(), v.z()}; }
Vector3 vector_of(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

// A three-axis value in config units read into an SI vector: `scale` converts SI -> config.
Vector3 axes_or(ParamReader& reader, std::string_view key, const Vector3& fallback_si,
                double scale, std::string_view unit) {
  return vector_of(reader.axes_or(key, array_of(fallback_si * scale), Bound::kNonNegative,
                                  unit)) /
         scale;
}

std::array<double, 3> signed_axes_or_zero(ParamReader& reader, std::string_view key,
                                          std::string_view unit) {
  return reader.axes_or(key, {0.0, 0.0, 0.0}, Bound::kAny, unit);
}

double number_in(ParamReader& reader, std::string_view key, double low, double high,
                 std::string_view unit) {
  const double value = reader.number(key, Bound::kAny, unit);
  if (!(value >= low && value <= high)) {
    throw ConfigError(reader.pointer(key) + ": " + std::to_string(value) +
                      (unit.empty() ? "" : " " + std::string(unit)) +
                      " is out of range; expected a value in [" +
                      std::to_string(low) + ", " + std::to_string(high) + "]");
  }
  return value;
}

std::uint64_t non_negative_integer(ParamReader& reader, std::string_view key) {
  const nlohmann::json& value = reader.raw(key);
  if (!value.is_number_integer() ||
      (!value.is_number_unsigned() && value.get<long long>() < 0)) {
    throw ConfigError(reader.pointer(key) + ": found " + value.dump() +
                      "; expected an integer >= 0");
  }
  return value.get<std::uint64_t>();
}

TieOnConfig parse_tie_on(const nlohmann::json& json, const std::string& pointer) {
  ParamReader reader(json, pointer);
  TieOnConfig tie_on;
  tie_on.latitude_deg = number_in(reader, "latitude_deg", -90.0, 90.0, "deg");
  tie_on.longitude_deg = number_in(reader, "longitude_deg", -360.0, 360.0, "deg");
  tie_on.height_m = reader.number("height_m", Bound::kAny, "m");
  if (reader.has("measured_depth_m")) {
    tie_on.measured_depth_m = reader.number("measured_depth_m", Bound::kAny, "m");
  }
  reader.finish();
  return tie_on;
}

AlignmentConfig parse_alignment(const nlohmann::json& json, const std::string& pointer) {
  ParamReader reader(json, pointer);
  AlignmentConfig alignment;
  alignment.static_s = reader.number("static_s", Bound::kPositive, "s");
  alignment.max_gyro_spread_deg_h = reader.number_or(
      "max_gyro_spread_deg_h", alignment.max_gyro_spread_deg_h, Bound::kPositive, "deg/h");
  alignment.max_accel_spread_m_s2 = reader.number_or(
      "max_accel_spread_m_s2", alignment.max_accel_spread_m_s2, Bound::kPositive, "m/s^2");
  alignment.zero_velocity_sigma_m_s =
      reader.number_or("zero_velocity_sigma_m_s", alignment.zero_velocity_sigma_m_s,
                       Bound::kPositive, "m/s");
  alignment.position_sigma_m = reader.number_or("position_sigma_m", alignment.position_sigma_m,
                                                Bound::kPositive, "m");
  if (reader.has("attitude_sigma_deg")) {
    alignment.attitude_sigma_deg = reader.axes("attitude_sigma_deg", Bound::kPositive, "deg");
  }
  reader.finish();
  return alignment;
}

InitialStateConfig parse_initial_state(const nlohmann::json& json, const std::string& pointer) {
  ParamReader reader(json, pointer);
  InitialStateConfig state;
  state.tie_on = parse_tie_on(object_at(reader, "tie_on", true), reader.pointer("tie_on"));
  const bool attitude = reader.has("attitude");
  const bool alignment = reader.has("alignment");
  if (attitude == alignment) {
    throw ConfigError(pointer + ": " +
                      (attitude ? std::string("both \"attitude\" and \"alignment\" given")
                                : std::string("no initial attitude")) +
                      "; expected either \"attitude\": {\"inclination_deg\", "
                      "\"azimuth_deg\", \"toolface_deg\"} or \"alignment\": "
                      "{\"static_s\": S}");
  }
  if (attitude) {
    ParamReader a(object_at(reader, "attitude", true), reader.pointer("attitude"));
    AttitudeConfig config;
    config.inclination_deg = number_in(a, "inclination_deg", 0.0, 180.0, "deg");
    config.azimuth_deg = a.number("azimuth_deg", Bound::kAny, "deg");
    config.toolface_deg = a.number("toolface_deg", Bound::kAny, "deg");
    a.finish();
    state.attitude = config;
  } else {
    state.alignment =
        parse_alignment(object_at(reader, "alignment", true), reader.pointer("alignment"));
  }
  state.velocity_m_s = signed_axes_or_zero(reader, "velocity_m_s", "m/s");
  if (state.alignment && vector_of(state.velocity_m_s).squaredNorm() > 0.0) {
    throw ConfigError(reader.pointer("velocity_m_s") +
                      ": a non-zero velocity with \"alignment\"; the alignment span is "
                      "static, so leave velocity_m_s out (zero)");
  }
  reader.finish();
  return state;
}

InitialErrorConfig parse_initial_error(const nlohmann::json& json, const std::string& pointer) {
  ParamReader reader(json, pointer);
  InitialErrorConfig error;
  error.position_m = signed_axes_or_zero(reader, "position_m", "m");
  error.velocity_m_s = signed_axes_or_zero(reader, "velocity_m_s", "m/s");
  error.attitude_deg = signed_axes_or_zero(reader, "attitude_deg", "deg");
  error.gyro_bias_deg_h = signed_axes_or_zero(reader, "gyro_bias_deg_h", "deg/h");
  error.accel_bias_m_s2 = signed_axes_or_zero(reader, "accel_bias_m_s2", "m/s^2");
  if (reader.has("draw_seed")) error.draw_seed = non_negative_integer(reader, "draw_seed");
  reader.finish();
  return error;
}

/// "survey"'s error-model keys (SurveyConfig): the files read here, so a bad one stops the
/// run before it starts.
void parse_survey_error_model(ParamReader& reader, const fs::path& config_dir,
                              SurveyConfig& survey) {
  if (reader.has("error_model")) {
    survey.error_model = reader.text("error_model");
    if (survey.error_model != "none") {
      survey_error::check_tool_model_name(survey.error_model, reader.pointer("error_model"));
    }
  }
  const bool gyro = survey.error_model == survey_error::kGyroNsCtModelName;
  const bool gyrocompass = survey_error::is_gyro_tool_model(survey.error_model);
  const auto only_with = [&](std::string_view key, bool allowed, std::string_view models) {
    if (!reader.has(key) || allowed) return;
    throw ConfigError(reader.pointer(key) + ": given with \"error_model\": \"" +
                      survey.error_model + "\"; it applies to " + std::string(models) +
                      " only: set \"error_model\" or drop it");
  };
  only_with("well", survey.error_model != "none", "an error model");
  only_with("noise_model", gyro, "\"gyro_ns_ct\"");
  only_with("gyrocompass_time_s", gyro, "\"gyro_ns_ct\"");
  only_with("running_speed_m_h", gyro, "\"gyro_ns_ct\"");
  if (reader.has("well")) {
    const std::string path = existing_file(reader, "well", config_dir).string();
    survey.well = survey_error::read_well_parameters(path);
    if (gyrocompass) survey_error::check_well_for_gyro(*survey.well, path);
  } else if (survey.error_model != "none" && !gyrocompass) {
    throw ConfigError(reader.pointer("well") + ": missing; \"error_model\": \"" +
                      survey.error_model +
                      "\" needs the well file of `stochnav survey --well` (magnetic field, "
                      "gravity; docs/survey-error-model.md)");
  }
  if (reader.has("noise_model")) {
    survey.gyro_noise_model = survey_error::read_gyro_noise_model(
        existing_file(reader, "noise_model", config_dir).string());
  }
  if (reader.has("gyrocompass_time_s")) {
    survey.gyrocompass_time_s = reader.number("gyrocompass_time_s", Bound::kPositive, "s");
  }
  if (reader.has("running_speed_m_h")) {
    survey.running_speed_m_h = reader.number("running_speed_m_h", Bound::kPositive, "m/h");
  }
}

SurveyConfig parse_survey(const nlohmann::json& json, const std::string& pointer,
                          const fs::path& config_dir) {
  ParamReader reader(json, pointer);
  SurveyConfig survey;
  if (reader.has("vertical_section_azimuth_deg")) {
    const double azimuth = reader.number("vertical_section_azimuth_deg", Bound::kAny, "deg");
    if (!(azimuth >= 0.0 && azimuth < 360.0)) {
      throw ConfigError(reader.pointer("vertical_section_azimuth_deg") + ": " +
                        std::to_string(azimuth) +
                        " deg is out of range; expected an azimuth from true north in [0, 360)");
    }
    survey.vertical_section_azimuth_deg = azimuth;
  }
  if (reader.has("ellipse_confidence")) {
    const double confidence = reader.number("ellipse_confidence", Bound::kAny, "");
    if (!(confidence > 0.0 && confidence < 1.0)) {
      throw ConfigError(reader.pointer("ellipse_confidence") + ": " + std::to_string(confidence) +
                        " is out of range; expected a probability in (0, 1), e.g. 0.95");
    }
    survey.ellipse_confidence = confidence;
  }
  if (reader.has("datum_elevation_m")) {
    survey.datum_elevation_m = number_in(reader, "datum_elevation_m", -10000.0, 10000.0, "m");
  }
  if (reader.has("tie_on_tvd_m")) {
    if (!survey.datum_elevation_m) {
      throw ConfigError(reader.pointer("tie_on_tvd_m") +
                        ": given without datum_elevation_m; add \"datum_elevation_m\" (the "
                        "depth datum's elevation above mean sea level, m)");
    }
    survey.tie_on_tvd_m = number_in(reader, "tie_on_tvd_m", -20000.0, 20000.0, "m");
  }
  if (reader.has("sensor_to_bit_m")) {
    survey.sensor_to_bit_m = number_in(reader, "sensor_to_bit_m", 0.0, 200.0, "m");
  }
  if (reader.has("tie_on_md_tolerance_m")) {
    const double tolerance = reader.number("tie_on_md_tolerance_m", Bound::kAny, "m");
    if (!(tolerance > 0.0 && tolerance <= 1000.0)) {
      throw ConfigError(reader.pointer("tie_on_md_tolerance_m") + ": " + std::to_string(tolerance) +
                        " m is out of range; expected a distance in (0, 1000] m, e.g. 5");
    }
    survey.tie_on_md_tolerance_m = tolerance;
  }
  if (reader.has("grid_convergence_deg")) {
    survey.grid_convergence_deg = number_in(reader, "grid_convergence_deg", -10.0, 10.0, "deg");
  }
  if (reader.has("well_reference")) {
    if (!survey.grid_convergence_deg) {
      throw ConfigError(reader.pointer("well_reference") +
                        ": given without grid_convergence_deg; add \"grid_convergence_deg\" "
                        "(grid north's angle from true north at the well, deg; 0 if the map's "
                        "grid north is true north there)");
    }
    ParamReader reference(object_at(reader, "well_reference", true),
                          reader.pointer("well_reference"));
    SurveyConfig::WellReference map;
    map.easting_m = number_in(reference, "easting_m", -1e8, 1e8, "m");
    map.northing_m = number_in(reference, "northing_m", -1e8, 1e8, "m");
    if (reference.has("scale_factor")) {
      map.scale_factor = number_in(reference, "scale_factor", 0.99, 1.01, "");
    }
    reference.finish();
    survey.well_reference = map;
  }
  if (reader.has("length_unit")) {
    static constexpr std::array<std::string_view, 2> kUnits = {"m", "ft"};
    survey.length_unit = reader.choice_or("length_unit", "m", kUnits);
  }
  parse_survey_error_model(reader, config_dir, survey);
  reader.finish();
  return survey;
}

}  // namespace

NoiseSection parse_noise_section(const nlohmann::json& json, const std::string& pointer,
                                 const fs::path& config_dir, const fs::path& default_record) {
  ParamReader section(json, pointer);
  NoiseSection noise;
  for (SensorGroup group : {SensorGroup::kGyro, SensorGroup::kAccel}) {
    const std::string key(sensor_group_name(group));
    const nlohmann::json& entry_json = object_at(section, key, true);
    ParamReader entry(entry_json, section.pointer(key));
    NoiseConfig config;
    static_cast<PluginConfig&>(config) = parse_plugin_entry(entry, section.pointer(key));
    const nlohmann::json& fit = entry.raw("fit");
    if (!fit.is_null()) {
      config.fit = parse_fit(fit, entry.pointer("fit"), group, config_dir, default_record);
    }
    const nlohmann::json& fit_options = entry.raw("fit_options");
    if (!fit_options.is_null()) {
      if (!fit_options.is_object()) {
        throw ConfigError(entry.pointer("fit_options") + ": found " +
                          fit_options.dump().substr(0, 40) +
                          "; expected an object of the fitter's options, e.g. {\"method\": "
                          "\"gmwm\"}");
      }
      if (!config.fit) {
        throw ConfigError(entry.pointer("fit_options") +
                          ": given without \"fit\"; add \"fit\": {} to fit the model from the "
                          "record, or give the model in \"params\"");
      }
      if (!config.params.empty()) {
        throw ConfigError(entry.pointer("params") +
                          ": given beside \"fit_options\"; a fitted model's keys go in "
                          "\"fit_options\" (move them there and remove \"params\")");
      }
      config.fit_options = fit_options;
    }
    entry.finish();
    (group == SensorGroup::kGyro ? noise.gyro : noise.accel) = std::move(config);
  }
  section.finish();
  return noise;
}

std::vector<PluginConfig> parse_aids_section(const nlohmann::json& json,
                                             const std::string& pointer) {
  if (!json.is_array()) {
    throw ConfigError(pointer + ": found " + json.dump().substr(0, 40) +
                      "; expected an array of {\"plugin\": TYPE, \"params\": {...}}");
  }
  std::vector<PluginConfig> aids;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const std::string item_pointer = pointer + "/" + std::to_string(i);
    if (!json[i].is_object()) {
      throw ConfigError(item_pointer +
                        ": not an object; expected {\"plugin\": TYPE, \"params\": {...}}");
    }
    ParamReader entry(json[i], item_pointer);
    aids.push_back(parse_plugin_entry(entry, item_pointer));
    entry.finish();
  }
  return aids;
}

DataConfig data_from_folder(const fs::path& dir) {
  std::error_code error;
  const std::string where = "--data " + dir.string();
  if (!fs::is_directory(dir, error)) {
    throw ConfigError(where + ": not a folder; give a recording folder holding imu.csv "
                              "(aids.csv and truth.csv optional)");
  }
  DataConfig data;
  data.imu = dir / kScenarioImuFile;
  if (!fs::is_regular_file(data.imu, error)) {
    throw ConfigError(where + ": no " + std::string(kScenarioImuFile) +
                      "; give a recording folder holding imu.csv (aids.csv and truth.csv "
                      "optional)");
  }
  if (fs::is_regular_file(dir / kScenarioTruthFile, error)) data.truth = dir / kScenarioTruthFile;
  if (fs::is_regular_file(dir / kScenarioAidsFile, error)) data.aids = dir / kScenarioAidsFile;
  // A `simulate scenario` folder: its scenario.json serves plugins that read it (oracle).
  if (fs::is_regular_file(dir / "scenario.json", error)) data.scenario_dir = dir;
  return data;
}

FilterConfig parse_filter_section(const nlohmann::json& json, const std::string& pointer) {
  ParamReader reader(json, pointer);
  FilterConfig config;
  FilterOptions& out = config.options;
  if (const auto& sigma = object_at(reader, "initial_sigma", false); !sigma.is_null()) {
    ParamReader s(sigma, reader.pointer("initial_sigma"));
    out.position_sigma_m = axes_or(s, "position_m", out.position_sigma_m, 1.0, "m");
    out.velocity_sigma_mps = axes_or(s, "velocity_m_s", out.velocity_sigma_mps, 1.0, "m/s");
    out.attitude_sigma_rad = axes_or(s, "attitude_deg", out.attitude_sigma_rad, kDegPerRad, "deg");
    out.accel_bias_sigma_mps2 =
        axes_or(s, "accel_bias_m_s2", out.accel_bias_sigma_mps2, 1.0, "m/s^2");
    out.gyro_bias_sigma_radps = axes_or(s, "gyro_bias_deg_h", out.gyro_bias_sigma_radps,
                                        kDegPerHourPerRadPerSecond, "deg/h");
    s.finish();
  }
  out.covariance_interval_s = reader.number_or("covariance_interval_s", out.covariance_interval_s,
                                               Bound::kNonNegative, "s");
  out.second_order_attitude_correlation_s =
      reader.number_or("second_order_attitude_correlation_s",
                       out.second_order_attitude_correlation_s, Bound::kNonNegative, "s");
  out.heading_hypothesis_sigma_rad =
      reader.number_or("heading_hypothesis_sigma_deg",
                       out.heading_hypothesis_sigma_rad * kDegPerRad, Bound::kNonNegative, "deg") /
      kDegPerRad;
  out.heading_hypotheses_consider_heading = reader.boolean_or(
      "heading_hypothesis_consider", out.heading_hypotheses_consider_heading);
  out.heading_hypotheses_robust_weights = reader.boolean_or(
      "heading_hypothesis_robust_weights", out.heading_hypotheses_robust_weights);
  out.heading_hypotheses_hold_together = reader.boolean_or(
      "heading_hypothesis_hold_together", out.heading_hypotheses_hold_together);
  out.heading_hypotheses_split_running = reader.boolean_or(
      "heading_hypothesis_split_running", out.heading_hypotheses_split_running);
  out.heading_hypotheses_mirror_at_rotation = reader.boolean_or(
      "heading_hypothesis_mirror_at_rotation", out.heading_hypotheses_mirror_at_rotation);
  if (reader.has("heading_hypothesis_likelihood_power")) {
    out.heading_hypotheses_likelihood_power =
        number_in(reader, "heading_hypothesis_likelihood_power", 0.05, 1.0, "");
  }
  out.vibration_velocity_threshold_mps =
      reader.number_or("vibration_velocity_threshold_m_s", out.vibration_velocity_threshold_mps,
                       Bound::kNonNegative, "m/s");
  if (reader.has("max_consecutive_rejections")) {
    const std::uint64_t count = non_negative_integer(reader, "max_consecutive_rejections");
    if (count > 1'000'000'000u) {
      throw ConfigError(reader.pointer("max_consecutive_rejections") + ": " +
                        std::to_string(count) + " is too large; expected an integer >= 0 "
                        "(0 keeps the gate strict)");
    }
    out.max_consecutive_rejections = static_cast<int>(count);
  }
  if (const auto& scale = object_at(reader, "scale_factor_sigma_ppm", false); !scale.is_null()) {
    ParamReader s(scale, reader.pointer("scale_factor_sigma_ppm"));
    out.gyro_scale_factor_sigma = axes_or(s, "gyro", out.gyro_scale_factor_sigma, 1.0 / kPpm, "ppm");
    out.accel_scale_factor_sigma =
        axes_or(s, "accel", out.accel_scale_factor_sigma, 1.0 / kPpm, "ppm");
    s.finish();
  }
  if (reader.has("feedback")) {
    const nlohmann::json& feedback = reader.raw("feedback");
    if (feedback != "closed_loop") {
      throw ConfigError(reader.pointer("feedback") + ": found " + feedback.dump() +
                        "; the navigator has one mode, \"closed_loop\" (every update fed back "
                        "into the INS): give it or leave the key out");
    }
  }
  reader.finish();
  return config;
}

RunConfig parse_run_config(const nlohmann::json& document, const fs::path& config_dir,
                           const std::optional<DataConfig>& data) {
  if (!document.is_object()) {
    throw ConfigError(
        "/: the run config is not a JSON object; expected {\"data\": ..., "
        "\"noise\": ..., ...}");
  }
  ParamReader root(document, "");
  RunConfig config;
  config.config_dir = config_dir;
  root.raw("description");  // free text for readers, ignored
  root.raw("comments");
  if (data) {
    root.raw("data");  // replaced by --data: neither read nor an unknown key
    config.data = *data;
  } else {
    config.data = parse_data(object_at(root, "data", true), root.pointer("data"), config_dir);
  }
  config.noise = parse_noise_section(object_at(root, "noise", true), root.pointer("noise"),
                                     config_dir, config.data.imu);
  if (const auto& aids = root.raw("aids"); !aids.is_null()) {
    config.aids = parse_aids_section(aids, root.pointer("aids"));
  }
  if (const auto& filter = object_at(root, "filter", false); !filter.is_null()) {
    config.filter = parse_filter_section(filter, root.pointer("filter"));
  }
  if (const auto& state = object_at(root, "initial_state", false); !state.is_null()) {
    config.initial_state = parse_initial_state(state, root.pointer("initial_state"));
  }
  if (const auto& error = object_at(root, "initial_error", false); !error.is_null()) {
    config.initial_error = parse_initial_error(error, root.pointer("initial_error"));
  }
  if (const auto& output = object_at(root, "output", false); !output.is_null()) {
    ParamReader reader(output, root.pointer("output"));
    if (reader.has("decimation")) {
      const auto& value = reader.raw("decimation");
      if (!value.is_number_integer() || value.get<long long>() < 1) {
        throw ConfigError(reader.pointer("decimation") + ": found " + value.dump() +
                          "; expected an integer >= 1");
      }
      config.output.decimation = value.get<std::size_t>();
    }
    config.output.covariance = reader.boolean_or("covariance", config.output.covariance);
    config.output.nees = reader.boolean_or("nees", config.output.nees);
    reader.finish();
  }
  if (const auto& survey = object_at(root, "survey", false); !survey.is_null()) {
    config.survey = parse_survey(survey, root.pointer("survey"), config_dir);
  }
  root.finish();
  return config;
}

void check_run_start(const RunConfig& config) {
  if (!config.data.truth && !config.initial_state) {
    throw ConfigError(
        "/initial_state: missing, and the data has no truth to start from; add "
        "\"initial_state\": {\"tie_on\": {\"latitude_deg\", \"longitude_deg\", "
        "\"height_m\"}, \"alignment\": {\"static_s\": S}} (or \"attitude\": {...})");
  }
}

RunConfig read_run_config(const fs::path& file, const std::optional<DataConfig>& data) {
  const nlohmann::json document = read_json_document(file, "the run config");
  return parse_run_config(document, fs::absolute(file).parent_path(), data);
}

RunConfig read_embedded_run_config(const fs::path& file) {
  return read_run_config(file, DataConfig{});
}

}  // namespace stochnav::plugin

#include "stochnav/scenario/scenario_config_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/nearest_name.hpp"
#include "stochnav/core/work_limits.hpp"
#include "stochnav/io/json_document.hpp"
#include "stochnav/model/noise_model_json.hpp"

namespace stochnav {
namespace {

using nlohmann::json;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kStandardGravity = 9.80665;   // m/s^2 per g
constexpr double kDegPerHour = kDeg / 3600.0;  // rad/s per deg/h
constexpr double kMilliG = 1e-3 * kStandardGravity;
constexpr double kMetrePerHour = 1.0 / 3600.0;  // m/s per m/h

[[noreturn]] void fail(const std::string& pointer, const std::string& problem,
                       std::string_view expected) {
  throw ConfigError(
      fmt::format("{}: {}; expected {}", pointer.empty() ? "(root)" : pointer, problem, expected));
}

std::string describe_type(const json& value) {
  return fmt::format("is {} {}", value.is_array() || value.is_object() ? "an" : "a",
                     value.type_name());
}

enum class Range { kAny, kPositive, kNonNegative };

// Reads the keys of one JSON object, remembering which it used so unknown keys are rejected.
class ObjectReader {
 public:
  ObjectReader(const json& value, std::string pointer, std::string form)
      : value_(value), pointer_(std::move(pointer)), form_(std::move(form)) {
    if (!value_.is_object()) fail(pointer_, describe_type(value_) + ", not an object", form_);
  }

  std::string at(std::string_view key) const { return pointer_ + "/" + std::string(key); }
  const std::string& pointer() const { return pointer_; }

  bool has(std::string_view key) {
    known_.insert(std::string(key));
    return value_.contains(key);
  }

  const json& get(std::string_view key) {
    if (!has(key)) fail_missing(key, form_);
    return value_.at(std::string(key));
  }

  double number(std::string_view key, std::string_view expected, Range range,
                std::optional<double> fallback = std::nullopt) {
    if (!has(key)) {
      if (fallback) return *fallback;
      fail_missing(key, expected);
    }
    return check_number(value_.at(std::string(key)), at(key), expected, range);
  }

  static double check_number(const json& value, const std::string& pointer,
                             std::string_view expected, Range range) {
    if (!value.is_number()) fail(pointer, describe_type(value) + ", not a number", expected);
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(pointer, "is not finite", expected);
    if (range == Range::kPositive && !(x > 0.0)) {
      fail(pointer, fmt::format("is {}, not > 0", x), expected);
    }
    if (range == Range::kNonNegative && x < 0.0) {
      fail(pointer, fmt::format("is {}, negative", x), expected);
    }
    return x;
  }

  std::string string(std::string_view key, std::string_view expected,
                     std::optional<std::string> fallback = std::nullopt) {
    if (!has(key)) {
      if (fallback) return *fallback;
      fail_missing(key, expected);
    }
    const json& v = value_.at(std::string(key));
    if (!v.is_string()) fail(at(key), describe_type(v) + ", not a string", expected);
    return v.get<std::string>();
  }

  // A likely typo of the missing key among the keys not read is reported as the typo.
  [[noreturn]] void fail_missing(std::string_view key, std::string_view expected) const {
    for (const auto& [name, entry] : value_.items()) {
      if (known_.contains(name) || !likely_typo(name, key)) continue;
      throw ConfigError(at(name) + ": unknown key '" + name + "'; did you mean '" +
                        std::string(key) + "'?");
    }
    fail(at(key), "is missing", expected);
  }

  void finish() const {
    for (const auto& [key, entry] : value_.items()) {
      if (key == "comments" || key == "comment") continue;  // free-text documentation
      if (known_.contains(key)) continue;
      const std::vector<std::string> names(known_.begin(), known_.end());
      if (const auto nearest = nearest_name(key, names)) {
        throw ConfigError(at(key) + ": unknown key '" + key + "'; did you mean '" + *nearest +
                          "'?");
      }
      fail(at(key), "is an unknown key", form_);
    }
  }

 private:
  const json& value_;
  std::string pointer_;
  std::string form_;
  std::set<std::string> known_;
};

// A number for all three axes or [x, y, z].
std::array<double, 3> axis_triple(const json& value, const std::string& pointer,
                                  std::string_view expected, double factor) {
  std::array<double, 3> out{};
  if (value.is_number()) {
    out.fill(ObjectReader::check_number(value, pointer, expected, Range::kAny) * factor);
    return out;
  }
  if (!value.is_array() || value.size() != 3) {
    fail(pointer, describe_type(value) + ", not a number or 3 numbers", expected);
  }
  for (std::size_t i = 0; i < 3; ++i) {
    out[i] = ObjectReader::check_number(value[i], pointer + "/" + std::to_string(i), expected,
                                        Range::kAny) *
             factor;
  }
  return out;
}

std::array<NoiseModel, 3> axis_models(const json& value, const std::string& pointer,
                                      Quantity quantity, bool allow_nonstationary) {
  std::array<NoiseModel, 3> models;
  const auto check = [&](const NoiseModel& model, const std::string& at) {
    if (quantity_of(model.unit) != quantity) {
      fail(at + "/units", fmt::format("is \"{}\"", unit_name(model.unit)),
           quantity == Quantity::kAngularRate ? "a rate unit: \"deg/h\", \"deg/s\" or \"rad/s\""
                                              : "a specific-force unit: \"m/s^2\" or \"g\"");
    }
    for (std::size_t t = 0; t < model.terms.size(); ++t) {
      if (!allow_nonstationary && term_type(model.terms[t]) == TermType::kNonstationary) {
        fail(fmt::format("{}/terms/{}", at, t), "is a nonstationary term in scheduled_noise",
             "no nonstationary term here: the phase noise scales build it");
      }
      if (!allow_nonstationary && term_type(model.terms[t]) == TermType::kAuxSensitivity) {
        fail(fmt::format("{}/terms/{}", at, t), "is an aux_sensitivity term in scheduled_noise",
             "the aux_sensitivity term under \"noise\" (the phase scales do not apply to it)");
      }
    }
  };
  if (value.is_array()) {
    if (value.size() != 3) {
      fail(pointer, fmt::format("has {} models", value.size()), "one model or 3 (x, y, z)");
    }
    for (std::size_t i = 0; i < 3; ++i) {
      const std::string at = pointer + "/" + std::to_string(i);
      models[i] = noise_model_from_json(value[i], at);
      check(models[i], at);
    }
  } else {
    models[0] = noise_model_from_json(value, pointer);
    check(models[0], pointer);
    models[1] = models[2] = models[0];
  }
  return models;
}

SensorErrorConfig parse_sensor(const json& value, const std::string& pointer, bool gyro) {
  const std::string bias_key = gyro ? "bias_dph" : "bias_mg";
  const std::string sigma_key = gyro ? "turn_on_bias_sigma_dph" : "turn_on_bias_sigma_mg";
  const double factor = gyro ? kDegPerHour : kMilliG;
  ObjectReader r(value, pointer,
                 fmt::format("{{\"noise\": MODEL | [MODEL, MODEL, MODEL], \"scheduled_noise\": "
                             "... (optional), \"{}\": [x, y, z], \"{}\": s, "
                             "\"scale_factor_ppm\": [x, y, z]}}",
                             bias_key, sigma_key));
  const Quantity quantity = gyro ? Quantity::kAngularRate : Quantity::kSpecificForce;
  SensorErrorConfig sensor;
  sensor.noise = axis_models(r.get("noise"), r.at("noise"), quantity, true);
  if (r.has("scheduled_noise")) {
    sensor.scheduled_noise =
        axis_models(r.get("scheduled_noise"), r.at("scheduled_noise"), quantity, false);
  } else {
    for (auto& m : sensor.scheduled_noise) m = NoiseModel{sensor.noise[0].unit, 100.0, {}};
  }
  const std::string triple =
      gyro ? "a bias in deg/h: a number or [x, y, z]" : "a bias in mg: a number or [x, y, z]";
  if (r.has(bias_key))
    sensor.constant_bias = axis_triple(r.get(bias_key), r.at(bias_key), triple, factor);
  sensor.turn_on_bias_sigma =
      r.number(sigma_key, gyro ? "a 1-sigma in deg/h >= 0" : "a 1-sigma in mg >= 0",
               Range::kNonNegative, 0.0) *
      factor;
  if (r.has("scale_factor_ppm")) {
    sensor.scale_factor = axis_triple(r.get("scale_factor_ppm"), r.at("scale_factor_ppm"),
                                      "a scale factor in ppm: a number or [x, y, z]", 1e-6);
  }
  r.finish();
  return sensor;
}

MwdAttitude parse_attitude(const json& value, const std::string& pointer) {
  ObjectReader r(value, pointer,
                 "{\"inclination_deg\": 0..180, \"toolface_deg\": x, \"azimuth_deg\": x}");
  MwdAttitude a;
  a.inclination_rad = r.number("inclination_deg", "an inclination in deg, 0..180", Range::kAny);
  if (a.inclination_rad < 0.0 || a.inclination_rad > 180.0) {
    fail(r.at("inclination_deg"), fmt::format("is {}", a.inclination_rad),
         "an inclination in deg, 0..180");
  }
  a.inclination_rad *= kDeg;
  a.toolface_rad = r.number("toolface_deg", "a toolface in deg", Range::kAny) * kDeg;
  a.azimuth_rad = r.number("azimuth_deg", "an azimuth in deg", Range::kAny) * kDeg;
  r.finish();
  return a;
}

RandomVibrationConfig parse_random(const json& value, const std::string& pointer) {
  ObjectReader r(value, pointer,
                 "{\"psd\": [[f_hz, g2_per_hz], ...], \"rms_g\": x, \"components\": n}");
  RandomVibrationConfig random;
  const json& psd = r.get("psd");
  constexpr std::string_view kRow = "[frequency Hz > 0, PSD g^2/Hz > 0], frequencies ascending";
  if (!psd.is_array() || psd.empty()) {
    fail(r.at("psd"), psd.is_array() ? "is empty" : describe_type(psd) + ", not an array",
         "a PSD table [[f_hz, g2_per_hz], ...] with at least one row");
  }
  for (std::size_t i = 0; i < psd.size(); ++i) {
    const std::string at = r.at("psd") + "/" + std::to_string(i);
    if (!psd[i].is_array() || psd[i].size() != 2) fail(at, "is not a pair", kRow);
    const double f = ObjectReader::check_number(psd[i][0], at + "/0", kRow, Range::kPositive);
    const double s = ObjectReader::check_number(psd[i][1], at + "/1", kRow, Range::kPositive);
    if (!random.psd.empty() && !(f > random.psd.back()[0])) {
      fail(at + "/0", fmt::format("is {} Hz, not above the previous row", f), kRow);
    }
    random.psd.push_back({f, s * kStandardGravity * kStandardGravity});
  }
  random.rms_mps2 =
      r.number("rms_g", "an RMS acceleration in g > 0", Range::kPositive) * kStandardGravity;
  const double components =
      r.number("components", "an integer number of sinusoids, 1..4096", Range::kPositive, 128.0);
  if (components != std::floor(components) || components > 4096) {
    fail(r.at("components"), fmt::format("is {}", components),
         "an integer number of sinusoids, 1..4096");
  }
  random.components = static_cast<int>(components);
  r.finish();
  return random;
}

VibrationTableConfig parse_table(const json& value, const std::string& pointer) {
  ObjectReader r(value, pointer, "{\"attitude\": {...}, \"phases\": [{...}, ...]}");
  VibrationTableConfig table;
  table.attitude = parse_attitude(r.get("attitude"), r.at("attitude"));
  const json& phases = r.get("phases");
  if (!phases.is_array() || phases.empty()) {
    fail(r.at("phases"), phases.is_array() ? "is empty" : describe_type(phases) + ", not an array",
         "a list of phases [{\"duration_s\": s, \"motion\": \"static\"}, ...]");
  }
  for (std::size_t i = 0; i < phases.size(); ++i) {
    const std::string at = r.at("phases") + "/" + std::to_string(i);
    ObjectReader p(phases[i], at,
                   "{\"name\": text, \"duration_s\": s > 0, \"motion\": \"static\" | \"sine\" | "
                   "\"random\", \"sine\": {...}, \"random\": {...}, \"gyro_noise_scale\": x, "
                   "\"accel_noise_scale\": x}");
    TablePhaseConfig phase;
    phase.name = p.string("name", "a phase name", std::string());
    phase.duration_s = p.number("duration_s", "a duration in s > 0", Range::kPositive);
    const std::string motion = p.string("motion", "\"static\", \"sine\" or \"random\"");
    if (motion == "static") {
      phase.motion = TableMotion::kStatic;
    } else if (motion == "sine") {
      phase.motion = TableMotion::kSine;
      ObjectReader s(p.get("sine"), p.at("sine"), "{\"frequency_hz\": f > 0, \"amplitude_g\": a}");
      phase.sine.frequency_hz = s.number("frequency_hz", "a frequency in Hz > 0", Range::kPositive);
      phase.sine.amplitude_mps2 =
          s.number("amplitude_g", "a peak acceleration in g >= 0", Range::kNonNegative) *
          kStandardGravity;
      s.finish();
    } else if (motion == "random") {
      phase.motion = TableMotion::kRandom;
      phase.random = parse_random(p.get("random"), p.at("random"));
    } else {
      fail(p.at("motion"), fmt::format("is \"{}\"", motion), "\"static\", \"sine\" or \"random\"");
    }
    phase.gyro_noise_scale = p.number(
        "gyro_noise_scale", "a factor >= 0 on the scheduled gyro noise", Range::kNonNegative, 1.0);
    phase.accel_noise_scale =
        p.number("accel_noise_scale", "a factor >= 0 on the scheduled accelerometer noise",
                 Range::kNonNegative, 1.0);
    p.finish();
    table.phases.push_back(std::move(phase));
  }
  r.finish();
  return table;
}

NoiseScales parse_scales(ObjectReader& parent, std::string_view key) {
  NoiseScales scales;
  if (!parent.has(key)) return scales;
  ObjectReader r(parent.get(key), parent.at(key), "{\"gyro\": x >= 0, \"accel\": x >= 0}");
  scales.gyro = r.number("gyro", "a factor >= 0", Range::kNonNegative, 1.0);
  scales.accel = r.number("accel", "a factor >= 0", Range::kNonNegative, 1.0);
  r.finish();
  return scales;
}

constexpr std::string_view kSectionForm =
    "{\"length_m\": m > 0, \"build_rate_deg_per_30m\": x, \"turn_rate_deg_per_30m\": x}";

WellPathConfig parse_well(const json& value, const std::string& pointer) {
  ObjectReader w(value, pointer,
                 "{\"kickoff_md_m\": m, \"build_rate_deg_per_30m\": x > 0, "
                 "\"target_inclination_deg\": 0 < x <= 90, \"azimuth_deg\": x, "
                 "\"turn_rate_deg_per_30m\": x} or {\"start\": {\"inclination_deg\", "
                 "\"azimuth_deg\"}, \"sections\": [" +
                     std::string(kSectionForm) + ", ...]}");
  WellPathConfig well;
  if (w.has("sections")) {
    for (const char* key : {"kickoff_md_m", "build_rate_deg_per_30m", "target_inclination_deg",
                            "azimuth_deg", "turn_rate_deg_per_30m"}) {
      if (w.has(key)) {
        fail(w.at(key), "cannot be combined with \"sections\"",
             "either \"sections\" (with an optional \"start\") or the kickoff / build / target "
             "form");
      }
    }
    if (w.has("start")) {
      ObjectReader start(w.get("start"), w.at("start"),
                         "{\"inclination_deg\": 0..180, \"azimuth_deg\": x}");
      const double inclination =
          start.number("inclination_deg", "an inclination in deg, 0..180", Range::kAny, 0.0);
      if (inclination < 0.0 || inclination > 180.0) {
        fail(start.at("inclination_deg"), fmt::format("is {}", inclination),
             "an inclination in deg, 0..180");
      }
      well.start_inclination_rad = inclination * kDeg;
      well.start_azimuth_rad =
          start.number("azimuth_deg", "an azimuth in deg", Range::kAny, 0.0) * kDeg;
      start.finish();
    }
    const json& sections = w.get("sections");
    if (!sections.is_array() || sections.empty()) {
      fail(w.at("sections"),
           sections.is_array() ? "is empty" : describe_type(sections) + ", not an array",
           "a list of sections [" + std::string(kSectionForm) + ", ...]");
    }
    double inclination_deg = well.start_inclination_rad / kDeg;
    for (std::size_t i = 0; i < sections.size(); ++i) {
      const std::string at = w.at("sections") + "/" + std::to_string(i);
      ObjectReader sr(sections[i], at, std::string(kSectionForm));
      WellSectionConfig section;
      section.length_m =
          sr.number("length_m", "a measured-depth length in m > 0", Range::kPositive);
      const double build = sr.number("build_rate_deg_per_30m",
                                     "a build rate in deg/30 m (negative: drop)", Range::kAny, 0.0);
      const double turn =
          sr.number("turn_rate_deg_per_30m", "a turn rate in deg/30 m (positive: clockwise)",
                    Range::kAny, 0.0);
      sr.finish();
      section.build_rate_rad_per_m = build * kDeg / 30.0;
      section.turn_rate_rad_per_m = turn * kDeg / 30.0;
      inclination_deg += build * section.length_m / 30.0;
      // Inclination is linear in md: its end value decides (1e-9 deg of rounding allowed).
      if (inclination_deg < -1e-9 || inclination_deg > 180.0 + 1e-9) {
        fail(at, fmt::format("drives the inclination to {:.6g} deg at its end", inclination_deg),
             "an inclination kept within 0..180 deg: a smaller build_rate_deg_per_30m or a "
             "shorter length_m");
      }
      well.sections.push_back(section);
    }
    w.finish();
    return well;
  }
  well.kickoff_md_m = w.number("kickoff_md_m", "a measured depth in m >= 0", Range::kNonNegative);
  well.build_rate_rad_per_m =
      w.number("build_rate_deg_per_30m", "a build rate in deg/30 m > 0", Range::kPositive) * kDeg /
      30.0;
  const double target =
      w.number("target_inclination_deg", "an inclination in deg, 0 < x <= 90", Range::kPositive);
  if (target > 90.0) {
    fail(w.at("target_inclination_deg"), fmt::format("is {}", target),
         "an inclination in deg, 0 < x <= 90");
  }
  well.target_inclination_rad = target * kDeg;
  well.azimuth_rad = w.number("azimuth_deg", "an azimuth in deg", Range::kAny) * kDeg;
  well.turn_rate_rad_per_m =
      w.number("turn_rate_deg_per_30m", "a turn rate in deg/30 m in the build", Range::kAny, 0.0) *
      kDeg / 30.0;
  w.finish();
  return well;
}

// "stand_pattern": the segments of every stand; defaults from rop_mph and rotation_rpm.
void parse_stand_pattern(ObjectReader& r, DrillingConfig& d) {
  constexpr std::string_view kForm =
      "[{\"mode\": \"rotate\", \"length_m\": m, \"rpm\": x, \"rop_mph\": x} | {\"mode\": "
      "\"slide\", \"length_m\": m, \"toolface_deg\": x, \"rop_mph\": x}, ...] with lengths "
      "summing to stand_length_m";
  const json& pattern = r.get("stand_pattern");
  if (!pattern.is_array() || pattern.empty()) {
    fail(r.at("stand_pattern"),
         pattern.is_array() ? "is empty" : describe_type(pattern) + ", not an array", kForm);
  }
  double total = 0.0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const std::string at = r.at("stand_pattern") + "/" + std::to_string(i);
    ObjectReader p(pattern[i], at,
                   "{\"mode\": \"rotate\" | \"slide\", \"length_m\": m > 0, \"rop_mph\": x > 0, "
                   "\"rpm\": x (rotate), \"toolface_deg\": x (slide)}");
    StandSegmentConfig segment;
    const std::string mode = p.string("mode", "\"rotate\" or \"slide\"");
    if (mode == "rotate") {
      segment.mode = DrillMode::kRotate;
    } else if (mode == "slide") {
      segment.mode = DrillMode::kSlide;
    } else {
      fail(p.at("mode"), fmt::format("is \"{}\"", mode), "\"rotate\" or \"slide\"");
    }
    segment.length_m = p.number("length_m", "a length in m > 0", Range::kPositive);
    segment.rop_mps = d.rop_mps;
    if (p.has("rop_mph")) {
      segment.rop_mps =
          p.number("rop_mph", "a rate of penetration in m/h > 0", Range::kPositive) * kMetrePerHour;
    }
    if (segment.mode == DrillMode::kSlide) {
      if (p.has("rpm")) {
        fail(p.at("rpm"), "is given for a slide segment",
             "no rpm in a slide (it holds toolface_deg); \"mode\": \"rotate\" to rotate");
      }
      segment.toolface_rad =
          p.number("toolface_deg", "the toolface in deg held while sliding", Range::kAny) * kDeg;
    } else {
      if (p.has("toolface_deg")) {
        fail(p.at("toolface_deg"), "is given for a rotate segment",
             "toolface_deg only in a slide segment (\"mode\": \"slide\")");
      }
      segment.rotation_radps = d.rotation_radps;
      if (p.has("rpm")) {
        segment.rotation_radps =
            p.number("rpm", "a rotation rate in rpm", Range::kAny) * 2.0 * std::numbers::pi / 60.0;
      }
    }
    if (!(segment.length_m > segment.rop_mps * d.ramp_s)) {
      fail(p.at("length_m"),
           fmt::format("is {} m: the ramps alone drill more at this ROP", segment.length_m),
           "length_m > rop * ramp_s (a longer segment, a lower ROP or a shorter ramp_s)");
    }
    p.finish();
    total += segment.length_m;
    d.stand_pattern.push_back(segment);
  }
  if (std::abs(total - d.stand_length_m) > 1e-9 * d.stand_length_m) {
    fail(r.at("stand_pattern"),
         fmt::format("has lengths summing to {} m, not stand_length_m {} m", total,
                     d.stand_length_m),
         "segment lengths summing to stand_length_m (change a length_m or stand_length_m)");
  }
}

// One vibration episode: by time {"start_s", "end_s", ...} or by depth {"start_md_m", ...}.

// The vibration of an episode, by time or by depth alike: its peak axial acceleration (m/s^2)
// and frequency (Hz); the last keys of the episode's object.
void read_axial_vibration(ObjectReader& e, double& amplitude_mps2, double& frequency_hz) {
  amplitude_mps2 =
      e.number("axial_g", "a peak axial acceleration in g >= 0", Range::kNonNegative) *
      kStandardGravity;
  frequency_hz = e.number("frequency_hz", "a frequency in Hz > 0", Range::kPositive);
  e.finish();
}

void parse_episode(const json& value, const std::string& at, DrillingConfig& d) {
  const bool by_depth =
      value.is_object() && (value.contains("start_md_m") || value.contains("end_md_m"));
  if (!by_depth) {
    ObjectReader e(value, at,
                   "{\"start_s\": s >= 0, \"end_s\": s > start_s, \"axial_g\": a >= 0, "
                   "\"frequency_hz\": f > 0} or {\"start_md_m\", \"end_md_m\", ...}, ascending "
                   "and not overlapping");
    VibrationEpisodeConfig episode;
    episode.start_s = e.number("start_s", "a time in s >= 0", Range::kNonNegative);
    episode.end_s = e.number("end_s", "a time in s > start_s", Range::kPositive);
    if (!(episode.end_s > episode.start_s)) {
      fail(e.at("end_s"), fmt::format("is {}, not after start_s", episode.end_s),
           "a time in s > start_s");
    }
    if (!d.vibration_episodes.empty() && episode.start_s < d.vibration_episodes.back().end_s) {
      fail(e.at("start_s"), "overlaps the previous episode",
           "episodes ascending and not overlapping");
    }
    read_axial_vibration(e, episode.axial_amplitude_mps2, episode.frequency_hz);
    d.vibration_episodes.push_back(episode);
    return;
  }
  ObjectReader e(value, at,
                 "{\"start_md_m\": m >= 0, \"end_md_m\": m > start_md_m, \"axial_g\": a >= 0, "
                 "\"frequency_hz\": f > 0}, depth episodes ascending and not overlapping");
  for (const char* key : {"start_s", "end_s"}) {
    if (e.has(key)) {
      fail(e.at(key), "is a time in a depth episode",
           "either start_s / end_s (by time) or start_md_m / end_md_m (by depth)");
    }
  }
  MdVibrationEpisodeConfig episode;
  episode.start_md_m = e.number("start_md_m", "a measured depth in m >= 0", Range::kNonNegative);
  episode.end_md_m = e.number("end_md_m", "a measured depth in m > start_md_m", Range::kPositive);
  if (!(episode.end_md_m > episode.start_md_m)) {
    fail(e.at("end_md_m"), fmt::format("is {}, not beyond start_md_m", episode.end_md_m),
         "a measured depth in m > start_md_m");
  }
  if (!d.md_vibration_episodes.empty() &&
      episode.start_md_m < d.md_vibration_episodes.back().end_md_m) {
    fail(e.at("start_md_m"), "overlaps the previous depth episode",
         "depth episodes ascending and not overlapping");
  }
  read_axial_vibration(e, episode.axial_amplitude_mps2, episode.frequency_hz);
  d.md_vibration_episodes.push_back(episode);
}

DrillingConfig parse_drilling(const json& value, const std::string& pointer) {
  ObjectReader r(value, pointer,
                 "{\"well\": {...}, \"start_md_m\", \"duration_s\", \"initial_static_s\", "
                 "\"rop_mph\", \"rotation_rpm\", \"initial_toolface_deg\", \"stand_length_m\", "
                 "\"connection_s\", \"ramp_s\", \"stand_pattern\", \"orient_s\", "
                 "\"vibration_episodes\", \"noise_scales\"}");
  DrillingConfig d;
  d.well = parse_well(r.get("well"), r.at("well"));
  d.start_md_m = r.number("start_md_m", "a measured depth in m >= 0", Range::kNonNegative, 0.0);
  d.duration_s = r.number("duration_s", "a duration in s > 0", Range::kPositive);
  d.initial_static_s =
      r.number("initial_static_s", "a duration in s >= 0", Range::kNonNegative, 0.0);
  d.rop_mps =
      r.number("rop_mph", "a rate of penetration in m/h > 0", Range::kPositive) * kMetrePerHour;
  d.rotation_radps =
      r.number("rotation_rpm", "a rotation rate in rpm (0 = sliding)", Range::kAny, 0.0) * 2.0 *
      std::numbers::pi / 60.0;
  d.initial_toolface_rad =
      r.number("initial_toolface_deg", "a toolface in deg", Range::kAny, 0.0) * kDeg;
  d.stand_length_m = r.number("stand_length_m", "a stand length in m > 0", Range::kPositive);
  d.connection_s = r.number("connection_s", "a duration in s >= 0", Range::kNonNegative);
  d.ramp_s = r.number("ramp_s", "a ramp duration in s > 0", Range::kPositive, 10.0);
  if (r.has("stand_pattern")) {
    parse_stand_pattern(r, d);
  } else if (!(d.stand_length_m > d.rop_mps * d.ramp_s)) {
    fail(r.at("ramp_s"), fmt::format("is {} s: the ramps alone drill more than a stand", d.ramp_s),
         "ramp_s < stand_length_m / rop");
  }
  if (r.has("orient_s")) {
    if (d.stand_pattern.empty()) {
      fail(r.at("orient_s"), "is given without \"stand_pattern\"",
           "orient_s only with a stand_pattern (remove it)");
    }
    d.orient_s = r.number("orient_s", "an orientation pause in s > 0", Range::kPositive);
  }
  if (r.has("vibration_episodes")) {
    const json& episodes = r.get("vibration_episodes");
    if (!episodes.is_array()) {
      fail(r.at("vibration_episodes"), describe_type(episodes) + ", not an array",
           "[{\"start_s\", \"end_s\", \"axial_g\", \"frequency_hz\"}, ...]");
    }
    for (std::size_t i = 0; i < episodes.size(); ++i) {
      parse_episode(episodes[i], r.at("vibration_episodes") + "/" + std::to_string(i), d);
    }
  }
  if (r.has("noise_scales")) {
    ObjectReader n(r.get("noise_scales"), r.at("noise_scales"),
                   "{\"static\": {...}, \"drilling\": {...}, \"vibration\": {...}}");
    d.static_noise = parse_scales(n, "static");
    d.drilling_noise = parse_scales(n, "drilling");
    d.vibration_noise = parse_scales(n, "vibration");
    n.finish();
  }
  r.finish();
  return d;
}

// aids: the timing of the aids.csv rows (a rig's clock, latency, gaps).
void parse_aid_timing(ObjectReader& aids, AidConfig& config) {
  config.clock_offset_s =
      aids.number("clock_offset_s", "a clock offset in s, |x| < 1", Range::kAny, 0.0);
  if (!(std::abs(config.clock_offset_s) < 1.0)) {
    fail(aids.at("clock_offset_s"), fmt::format("is {}", config.clock_offset_s),
         "a clock offset in s, |x| < 1");
  }
  config.latency_s = aids.number("latency_s", "a latency in s >= 0", Range::kNonNegative, 0.0);
  if (!aids.has("dropouts")) return;
  constexpr std::string_view kForm =
      "[{\"start_s\": s >= 0, \"end_s\": s > start_s}, ...] ascending and not overlapping";
  const json& dropouts = aids.get("dropouts");
  if (!dropouts.is_array()) {
    fail(aids.at("dropouts"), describe_type(dropouts) + ", not an array", kForm);
  }
  for (std::size_t i = 0; i < dropouts.size(); ++i) {
    const std::string at = aids.at("dropouts") + "/" + std::to_string(i);
    ObjectReader d(dropouts[i], at, std::string(kForm));
    const double start = d.number("start_s", "a time in s >= 0", Range::kNonNegative);
    const double end = d.number("end_s", "a time in s > start_s", Range::kNonNegative);
    if (!(end > start)) {
      fail(d.at("end_s"), fmt::format("is {}, not after start_s {}", end, start),
           "a time in s > start_s");
    }
    if (!config.dropouts.empty() && start <= config.dropouts.back()[1]) {
      fail(d.at("start_s"), "overlaps or touches the previous dropout",
           "dropouts ascending and not overlapping (merge them into one)");
    }
    d.finish();
    config.dropouts.push_back({start, end});
  }
}

void check_rate_divides(ObjectReader& r, std::string_view key, double rate, double imu_rate) {
  const double ratio = imu_rate / rate;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio) {
    fail(r.at(key), fmt::format("is {} Hz, which does not divide rate_hz {} Hz", rate, imu_rate),
         "a rate such that rate_hz / rate is an integer");
  }
}

ScenarioConfig parse(const json& value) {
  ObjectReader r(value, "",
                 "a scenario {\"kind\", \"imu\", \"site\", \"sensors\", \"vibration_table\" | "
                 "\"drilling\", ...}");
  ScenarioConfig config;
  config.description = r.string("description", "a text", std::string());
  const std::string kind = r.string("kind", "\"vibration_table\" or \"drilling\"");
  if (kind == "vibration_table") {
    config.kind = ScenarioKind::kVibrationTable;
  } else if (kind == "drilling") {
    config.kind = ScenarioKind::kDrilling;
  } else {
    fail(r.at("kind"), fmt::format("is \"{}\"", kind), "\"vibration_table\" or \"drilling\"");
  }
  if (r.has("seed")) {
    const json& seed = r.get("seed");
    if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<long long>() >= 0)) {
      fail(r.at("seed"), describe_type(seed), "an integer >= 0");
    }
    config.seed = seed.get<std::uint64_t>();
  }
  {
    ObjectReader imu(r.get("imu"), r.at("imu"),
                     "{\"rate_hz\": 100..1000, \"output\": \"increments\" | \"rates\", "
                     "\"truth_rate_hz\": f, \"aid_rate_hz\": f}");
    config.imu.rate_hz = imu.number("rate_hz", "an IMU rate in Hz, 100..1000", Range::kPositive);
    if (config.imu.rate_hz < 100.0 || config.imu.rate_hz > 1000.0) {
      fail(imu.at("rate_hz"), fmt::format("is {}", config.imu.rate_hz),
           "an IMU rate in Hz, 100..1000");
    }
    const std::string output =
        imu.string("output", "\"increments\" or \"rates\"", std::string("increments"));
    if (output == "increments") {
      config.imu.output = ImuOutput::kIncrements;
    } else if (output == "rates") {
      config.imu.output = ImuOutput::kRates;
    } else {
      fail(imu.at("output"), fmt::format("is \"{}\"", output), "\"increments\" or \"rates\"");
    }
    config.imu.truth_rate_hz = imu.number("truth_rate_hz", "a rate in Hz > 0 dividing rate_hz",
                                          Range::kPositive, config.imu.rate_hz);
    check_rate_divides(imu, "truth_rate_hz", config.imu.truth_rate_hz, config.imu.rate_hz);
    config.imu.aid_rate_hz =
        imu.number("aid_rate_hz", "a rate in Hz > 0 dividing rate_hz", Range::kPositive, 1.0);
    check_rate_divides(imu, "aid_rate_hz", config.imu.aid_rate_hz, config.imu.rate_hz);
    imu.finish();
  }
  {
    ObjectReader site(r.get("site"), r.at("site"),
                      "{\"latitude_deg\": -89..89, \"longitude_deg\": x, \"height_m\": h}");
    const double latitude = site.number("latitude_deg", "a latitude in deg, -89..89", Range::kAny);
    if (std::abs(latitude) > 89.0) {
      fail(site.at("latitude_deg"), fmt::format("is {}", latitude), "a latitude in deg, -89..89");
    }
    config.site.latitude_rad = latitude * kDeg;
    config.site.longitude_rad =
        site.number("longitude_deg", "a longitude in deg", Range::kAny) * kDeg;
    config.site.height_m = site.number("height_m", "an ellipsoidal height in m", Range::kAny, 0.0);
    site.finish();
  }
  {
    ObjectReader sensors(r.get("sensors"), r.at("sensors"), "{\"gyro\": {...}, \"accel\": {...}}");
    config.gyro = parse_sensor(sensors.get("gyro"), sensors.at("gyro"), true);
    config.accel = parse_sensor(sensors.get("accel"), sensors.at("accel"), false);
    sensors.finish();
  }
  if (r.has("aids")) {
    ObjectReader aids(r.get("aids"), r.at("aids"),
                      "{\"depth_scale_error\": x, \"depth_noise_m\": s >= 0, "
                      "\"rop_noise_mph\": s >= 0, \"clock_offset_s\": |x| < 1, "
                      "\"latency_s\": s >= 0, \"dropouts\": [{\"start_s\", \"end_s\"}, ...]}");
    config.aids.depth_scale_error =
        aids.number("depth_scale_error", "a relative error (1e-3 = 0.1 %)", Range::kAny, 0.0);
    config.aids.depth_noise_m =
        aids.number("depth_noise_m", "a 1-sigma in m >= 0", Range::kNonNegative, 0.0);
    config.aids.rop_noise_mps =
        aids.number("rop_noise_mph", "a 1-sigma in m/h >= 0", Range::kNonNegative, 0.0) *
        kMetrePerHour;
    parse_aid_timing(aids, config.aids);
    aids.finish();
  }
  for (const char* key : {"noise_variance_scale", "moving_noise_variance_scale"}) {
    if (!r.has(key)) continue;
    ObjectReader n(r.get(key), r.at(key), "{\"gyro\": x >= 0, \"accel\": x >= 0}");
    NoiseScales& scales = std::string_view(key) == "noise_variance_scale"
                              ? config.noise_variance_scale
                              : config.moving_noise_variance_scale;
    scales.gyro = n.number("gyro", "a factor >= 0 on the scheduled gyro noise variance",
                           Range::kNonNegative, 1.0);
    scales.accel = n.number("accel", "a factor >= 0 on the scheduled accelerometer noise variance",
                            Range::kNonNegative, 1.0);
    n.finish();
  }
  if (config.kind == ScenarioKind::kVibrationTable) {
    config.vibration_table = parse_table(r.get("vibration_table"), r.at("vibration_table"));
  } else {
    config.drilling = parse_drilling(r.get("drilling"), r.at("drilling"));
  }
  r.finish();
  const double epochs = scenario_duration_s(config) * config.imu.rate_hz;
  if (epochs < 2.0 || epochs > limits::kMaxScenarioEpochs) {
    fail(
        config.kind == ScenarioKind::kDrilling ? "/drilling/duration_s" : "/vibration_table/phases",
        fmt::format("gives {:.3g} IMU epochs", epochs),
        fmt::format("a duration of 2 to {:.3g} epochs at imu/rate_hz (the limit on work, "
                    "docs/reliability.md)", limits::kMaxScenarioEpochs));
  }
  return config;
}

json sensor_json(const SensorErrorConfig& sensor, bool gyro) {
  const double factor = gyro ? kDegPerHour : kMilliG;
  json noise = json::array();
  json scheduled = json::array();
  for (std::size_t i = 0; i < 3; ++i) {
    noise.push_back(to_json(sensor.noise[i]));
    scheduled.push_back(to_json(sensor.scheduled_noise[i]));
  }
  json out;
  out["noise"] = noise;
  out["scheduled_noise"] = scheduled;
  json bias = json::array();
  json scale = json::array();
  for (std::size_t i = 0; i < 3; ++i) {
    bias.push_back(sensor.constant_bias[i] / factor);
    scale.push_back(sensor.scale_factor[i] / 1e-6);
  }
  out[gyro ? "bias_dph" : "bias_mg"] = bias;
  out[gyro ? "turn_on_bias_sigma_dph" : "turn_on_bias_sigma_mg"] =
      sensor.turn_on_bias_sigma / factor;
  out["scale_factor_ppm"] = scale;
  return out;
}

json well_json(const WellPathConfig& well) {
  if (well.sections.empty()) {
    json out = {{"kickoff_md_m", well.kickoff_md_m},
                {"build_rate_deg_per_30m", well.build_rate_rad_per_m * 30.0 / kDeg},
                {"target_inclination_deg", well.target_inclination_rad / kDeg},
                {"azimuth_deg", well.azimuth_rad / kDeg}};
    if (well.turn_rate_rad_per_m != 0.0) {
      out["turn_rate_deg_per_30m"] = well.turn_rate_rad_per_m * 30.0 / kDeg;
    }
    return out;
  }
  json sections = json::array();
  for (const auto& s : well.sections) {
    sections.push_back({{"length_m", s.length_m},
                        {"build_rate_deg_per_30m", s.build_rate_rad_per_m * 30.0 / kDeg},
                        {"turn_rate_deg_per_30m", s.turn_rate_rad_per_m * 30.0 / kDeg}});
  }
  return {{"start",
           {{"inclination_deg", well.start_inclination_rad / kDeg},
            {"azimuth_deg", well.start_azimuth_rad / kDeg}}},
          {"sections", sections}};
}

std::string_view motion_name(TableMotion motion) {
  switch (motion) {
    case TableMotion::kSine:
      return "sine";
    case TableMotion::kRandom:
      return "random";
    case TableMotion::kStatic:
      break;
  }
  return "static";
}

}  // namespace

double scenario_duration_s(const ScenarioConfig& config) {
  if (config.kind == ScenarioKind::kDrilling)
    return config.drilling ? config.drilling->duration_s : 0.0;
  double total = 0.0;
  if (config.vibration_table) {
    for (const auto& phase : config.vibration_table->phases) total += phase.duration_s;
  }
  return total;
}

ScenarioConfig scenario_config_from_json(const json& value, std::string_view source) {
  try {
    return parse(value);
  } catch (const ConfigError& error) {
    throw ConfigError(fmt::format("{}: {}", source, error.what()));
  }
}

json to_json(const ScenarioConfig& config) {
  json out;
  out["description"] = config.description;
  out["kind"] = config.kind == ScenarioKind::kDrilling ? "drilling" : "vibration_table";
  out["seed"] = config.seed;
  out["imu"] = {{"rate_hz", config.imu.rate_hz},
                {"output", config.imu.output == ImuOutput::kRates ? "rates" : "increments"},
                {"truth_rate_hz", config.imu.truth_rate_hz},
                {"aid_rate_hz", config.imu.aid_rate_hz}};
  out["site"] = {{"latitude_deg", config.site.latitude_rad / kDeg},
                 {"longitude_deg", config.site.longitude_rad / kDeg},
                 {"height_m", config.site.height_m}};
  out["sensors"] = {{"gyro", sensor_json(config.gyro, true)},
                    {"accel", sensor_json(config.accel, false)}};
  if (config.noise_variance_scale.gyro != 1.0 || config.noise_variance_scale.accel != 1.0) {
    out["noise_variance_scale"] = {{"gyro", config.noise_variance_scale.gyro},
                                   {"accel", config.noise_variance_scale.accel}};
  }
  if (config.moving_noise_variance_scale.gyro != 1.0 ||
      config.moving_noise_variance_scale.accel != 1.0) {
    out["moving_noise_variance_scale"] = {{"gyro", config.moving_noise_variance_scale.gyro},
                                          {"accel", config.moving_noise_variance_scale.accel}};
  }
  out["aids"] = {{"depth_scale_error", config.aids.depth_scale_error},
                 {"depth_noise_m", config.aids.depth_noise_m},
                 {"rop_noise_mph", config.aids.rop_noise_mps / kMetrePerHour}};
  // The timing keys only when used (echoes of configurations without them are unchanged).
  if (config.aids.clock_offset_s != 0.0) out["aids"]["clock_offset_s"] = config.aids.clock_offset_s;
  if (config.aids.latency_s != 0.0) out["aids"]["latency_s"] = config.aids.latency_s;
  if (!config.aids.dropouts.empty()) {
    json dropouts = json::array();
    for (const auto& d : config.aids.dropouts) {
      dropouts.push_back({{"start_s", d[0]}, {"end_s", d[1]}});
    }
    out["aids"]["dropouts"] = dropouts;
  }
  if (config.vibration_table) {
    const auto& t = *config.vibration_table;
    json phases = json::array();
    for (const auto& p : t.phases) {
      json phase = {{"name", p.name},
                    {"duration_s", p.duration_s},
                    {"motion", motion_name(p.motion)},
                    {"gyro_noise_scale", p.gyro_noise_scale},
                    {"accel_noise_scale", p.accel_noise_scale}};
      if (p.motion == TableMotion::kSine) {
        phase["sine"] = {{"frequency_hz", p.sine.frequency_hz},
                         {"amplitude_g", p.sine.amplitude_mps2 / kStandardGravity}};
      } else if (p.motion == TableMotion::kRandom) {
        json psd = json::array();
        for (const auto& row : p.random.psd) {
          psd.push_back({row[0], row[1] / (kStandardGravity * kStandardGravity)});
        }
        phase["random"] = {{"psd", psd},
                           {"rms_g", p.random.rms_mps2 / kStandardGravity},
                           {"components", p.random.components}};
      }
      phases.push_back(std::move(phase));
    }
    out["vibration_table"] = {{"attitude",
                               {{"inclination_deg", t.attitude.inclination_rad / kDeg},
                                {"toolface_deg", t.attitude.toolface_rad / kDeg},
                                {"azimuth_deg", t.attitude.azimuth_rad / kDeg}}},
                              {"phases", phases}};
  }
  if (config.drilling) {
    const auto& d = *config.drilling;
    json episodes = json::array();
    for (const auto& e : d.vibration_episodes) {
      episodes.push_back({{"start_s", e.start_s},
                          {"end_s", e.end_s},
                          {"axial_g", e.axial_amplitude_mps2 / kStandardGravity},
                          {"frequency_hz", e.frequency_hz}});
    }
    const auto scales = [](const NoiseScales& s) {
      return json{{"gyro", s.gyro}, {"accel", s.accel}};
    };
    for (const auto& e : d.md_vibration_episodes) {
      episodes.push_back({{"start_md_m", e.start_md_m},
                          {"end_md_m", e.end_md_m},
                          {"axial_g", e.axial_amplitude_mps2 / kStandardGravity},
                          {"frequency_hz", e.frequency_hz}});
    }
    out["drilling"] = {{"well", well_json(d.well)},
                       {"start_md_m", d.start_md_m},
                       {"duration_s", d.duration_s},
                       {"initial_static_s", d.initial_static_s},
                       {"rop_mph", d.rop_mps / kMetrePerHour},
                       {"rotation_rpm", d.rotation_radps * 60.0 / (2.0 * std::numbers::pi)},
                       {"initial_toolface_deg", d.initial_toolface_rad / kDeg},
                       {"stand_length_m", d.stand_length_m},
                       {"connection_s", d.connection_s},
                       {"ramp_s", d.ramp_s},
                       {"vibration_episodes", episodes},
                       {"noise_scales",
                        {{"static", scales(d.static_noise)},
                         {"drilling", scales(d.drilling_noise)},
                         {"vibration", scales(d.vibration_noise)}}}};
    if (!d.stand_pattern.empty()) {
      json pattern = json::array();
      for (const auto& p : d.stand_pattern) {
        json segment = {{"mode", p.mode == DrillMode::kSlide ? "slide" : "rotate"},
                        {"length_m", p.length_m},
                        {"rop_mph", p.rop_mps / kMetrePerHour}};
        if (p.mode == DrillMode::kSlide) {
          segment["toolface_deg"] = p.toolface_rad / kDeg;
        } else {
          segment["rpm"] = p.rotation_radps * 60.0 / (2.0 * std::numbers::pi);
        }
        pattern.push_back(std::move(segment));
      }
      out["drilling"]["stand_pattern"] = std::move(pattern);
      out["drilling"]["orient_s"] = d.orient_s;
    }
  }
  return out;
}

ScenarioConfig read_scenario_config(const std::filesystem::path& file) {
  return scenario_config_from_json(read_json_document(file, "the scenario config"), file.string());
}

}  // namespace stochnav

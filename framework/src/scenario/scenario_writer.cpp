#include "stochnav/scenario/scenario_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/progress_bar.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"
#include "stochnav/scenario/scenario_simulator.hpp"
#include "stochnav/sim/normal_generator.hpp"
#include "stochnav/version.hpp"

namespace stochnav {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr double kMpsToMph = 3600.0;

// A CSV file written through a large buffer into a PendingFile's temporary path.
class CsvStream {
 public:
  CsvStream(const std::filesystem::path& path, std::string_view header)
      : pending_(path), display_(path.string()) {
    file_ = pending_.open_file();
    buffer_.append(header);
    buffer_.push_back('\n');
  }
  ~CsvStream() {
    if (file_ != nullptr) std::fclose(file_);
  }
  CsvStream(const CsvStream&) = delete;
  CsvStream& operator=(const CsvStream&) = delete;

  fmt::memory_buffer& buffer() { return buffer_; }
  void maybe_flush() {
    if (buffer_.size() > (1u << 20)) flush();
  }
  void flush() {
    if (buffer_.size() > 0 &&
        std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) {
      throw_write_error(display_, errno);
    }
    buffer_.clear();
  }
  /// Flushes and closes; the rename happens in commit().
  void close() {
    flush();
    const int status = std::fclose(file_);
    file_ = nullptr;
    if (status != 0) throw_write_error(display_, errno);
  }
  void commit() { pending_.commit(); }

 private:
  PendingFile pending_;
  std::string display_;
  std::FILE* file_ = nullptr;
  fmt::memory_buffer buffer_;
};

void append_truth(fmt::memory_buffer& out, const TruthSample& truth) {
  const MwdAttitude attitude = mwd_from_dcm(truth.C_nb);
  // "+ 0.0" turns -0 into 0.
  fmt::format_to(std::back_inserter(out), "{},{},{},{},{},{},{},{},{},{}\n", truth.t_s,
                 truth.latitude_rad * kRadToDeg, truth.longitude_rad * kRadToDeg, truth.height_m,
                 truth.v_n.x() + 0.0, truth.v_n.y() + 0.0, truth.v_n.z() + 0.0,
                 attitude.inclination_rad * kRadToDeg, attitude.toolface_rad * kRadToDeg,
                 attitude.azimuth_rad * kRadToDeg);
}

// The auxiliary channels (temperature) that the gyro and accelerometer aux_sensitivity terms
// read, one per column; the first term naming a column gives its profile (as `simulate noise`).
std::vector<AuxSensitivityTerm> aux_channels(const ScenarioConfig& config) {
  std::vector<AuxSensitivityTerm> channels;
  for (const SensorErrorConfig* sensor : {&config.gyro, &config.accel}) {
    for (const NoiseModel& model : sensor->noise) {
      for (const NoiseTerm& term : model.terms) {
        const auto* aux = std::get_if<AuxSensitivityTerm>(&term);
        if (aux == nullptr) continue;
        const bool seen = std::any_of(channels.begin(), channels.end(),
                                      [&](const auto& c) { return c.column == aux->column; });
        if (!seen) channels.push_back(*aux);
      }
    }
  }
  return channels;
}

}  // namespace

ScenarioRunSummary write_scenario_outputs(const ScenarioConfig& config,
                                          const ScenarioOutputOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ScenarioConfig run_config = config;
  run_config.seed = options.seed;
  ScenarioSimulator simulator(run_config, options.seed);  // configuration errors first
  OutputFolder out_folder(options.out_dir);

  // Column names say what the numbers are (experiment/navigation_files.hpp reads both forms).
  CsvStream imu(options.out_dir / "imu.csv",
                config.imu.output == ImuOutput::kIncrements
                    ? "t,dtheta_x,dtheta_y,dtheta_z,dv_x,dv_y,dv_z"
                    : "t,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z");
  CsvStream truth(options.out_dir / "truth.csv",
                  "t,lat,lon,h,ve,vn,vu,inclination,toolface,azimuth");
  // Auxiliary channels go after the fixed columns, so files without them are unchanged.
  const std::vector<AuxSensitivityTerm> channels = aux_channels(config);
  std::vector<std::string> aid_columns = {"t",    "measured_depth_m",      "rop_mph",
                                          "zupt", "measured_depth_true_m", "rop_true_mph"};
  std::vector<std::string> aid_units = {"s", "m", "m/h", "flag", "m", "m/h"};
  for (const auto& channel : channels) {
    if (std::find(aid_columns.begin(), aid_columns.end(), channel.column) != aid_columns.end()) {
      throw ConfigError("simulate scenario: aux_sensitivity column \"" + channel.column +
                        "\" is already a column of aids.csv; rename it");
    }
    aid_columns.push_back(channel.column);
    aid_units.push_back("channel");
  }
  std::string aid_header;
  for (const auto& column : aid_columns) aid_header += (aid_header.empty() ? "" : ",") + column;
  CsvStream aids(options.out_dir / "aids.csv", aid_header);
  PendingFile scenario_json(options.out_dir / "scenario.json");

  const double rate = simulator.rate_hz();
  const auto truth_every =
      static_cast<std::uint64_t>(std::llround(rate / config.imu.truth_rate_hz));
  const auto aid_every = static_cast<std::uint64_t>(std::llround(rate / config.imu.aid_rate_hz));
  NormalGenerator aid_noise(derive_stream_seed(options.seed, 4000));
  const AidConfig& timing = config.aids;
  // With latency the readings come from a second copy of the motion, so the one that integrates
  // the IMU is queried exactly as without it.
  const std::unique_ptr<TrueMotion> delayed_motion =
      timing.latency_s > 0.0 ? make_true_motion(run_config, options.seed) : nullptr;
  const auto append_aid = [&](const TruthSample& t) {
    TruthSample delayed;
    if (delayed_motion) delayed = delayed_motion->truth(std::max(0.0, t.t_s - timing.latency_s));
    const TruthSample& read = delayed_motion ? delayed : t;
    const double depth = read.measured_depth_m * (1.0 + config.aids.depth_scale_error) +
                         config.aids.depth_noise_m * aid_noise();
    const double rop = read.rop_mps + config.aids.rop_noise_mps * aid_noise();
    // A dropped row still draws its noise: the other rows are those of the run without gaps.
    const bool dropped = std::any_of(timing.dropouts.begin(), timing.dropouts.end(),
                                     [&](const auto& d) { return t.t_s >= d[0] && t.t_s <= d[1]; });
    if (dropped) return;
    const double written_t = timing.clock_offset_s != 0.0 ? t.t_s + timing.clock_offset_s : t.t_s;
    fmt::format_to(std::back_inserter(aids.buffer()), "{},{},{},{},{},{}", written_t, depth,
                   rop * kMpsToMph, read.stationary ? 1 : 0, t.measured_depth_m,
                   t.rop_mps * kMpsToMph);
    // The channel at the aid time itself (the IMU sampler reads it at interval midpoints).
    for (const auto& channel : channels) {
      fmt::format_to(std::back_inserter(aids.buffer()), ",{}", channel.profile_at(t.t_s));
    }
    aids.buffer().push_back('\n');
  };
  const TruthSample initial = simulator.initial_truth();
  append_truth(truth.buffer(), initial);
  append_aid(initial);

  const bool rates = config.imu.output == ImuOutput::kRates;
  ScenarioEpoch epoch;
  const std::uint64_t count = simulator.epoch_count();
  ProgressBar progress("simulate scenario", count, options.progress);
  for (std::uint64_t k = 1; k <= count; ++k) {
    const bool truth_row = k % truth_every == 0;
    const bool aid_row = k % aid_every == 0;
    simulator.next(epoch, truth_row || aid_row);
    const ImuIncrement& m = epoch.measured;
    const double factor = rates ? 1.0 / m.dt_s : 1.0;
    fmt::format_to(std::back_inserter(imu.buffer()), "{},{},{},{},{},{},{}\n", m.t_s,
                   m.delta_theta_b.x() * factor, m.delta_theta_b.y() * factor,
                   m.delta_theta_b.z() * factor, m.delta_v_b.x() * factor, m.delta_v_b.y() * factor,
                   m.delta_v_b.z() * factor);
    imu.maybe_flush();
    if (truth_row) {
      append_truth(truth.buffer(), epoch.truth);
      truth.maybe_flush();
    }
    if (aid_row) {
      append_aid(epoch.truth);
      aids.maybe_flush();
    }
    progress.update(k);
  }
  progress.finish(count);

  nlohmann::json document;
  document["stochnav_version"] = std::string(kVersion);
  document["source"] = options.source;
  document["seed"] = options.seed;
  document["epochs"] = count;
  document["duration_s"] = simulator.motion().duration_s();
  document["config"] = to_json(run_config);
  document["files"] = {
      {"imu.csv",
       {{"columns", rates ? nlohmann::json({"t", "gyro_x", "gyro_y", "gyro_z", "accel_x",
                                            "accel_y", "accel_z"})
                          : nlohmann::json({"t", "dtheta_x", "dtheta_y", "dtheta_z", "dv_x",
                                            "dv_y", "dv_z"})},
        {"units", rates ? nlohmann::json({"s", "rad/s", "rad/s", "rad/s", "m/s^2", "m/s^2",
                                          "m/s^2"})
                        : nlohmann::json({"s", "rad", "rad", "rad", "m/s", "m/s", "m/s"})},
        {"meaning", rates ? "mean angular rate and specific force over (t - 1/rate_hz, t], "
                            "body frame"
                          : "delta-theta and delta-v over (t - 1/rate_hz, t], body frame"}}},
      {"truth.csv",
       {{"columns",
         {"t", "lat", "lon", "h", "ve", "vn", "vu", "inclination", "toolface", "azimuth"}},
        {"units", {"s", "deg", "deg", "m", "m/s", "m/s", "m/s", "deg", "deg", "deg"}},
        {"meaning",
         "true state at t: WGS-84 geodetic position, ellipsoidal height, ENU velocity, MWD "
         "attitude (near vertical: azimuth 0 and the gyro toolface)"}}},
      {"aids.csv",
       {{"columns", aid_columns},
        {"units", aid_units},
        {"meaning",
         channels.empty()
             ? "measured depth = true (1 + depth_scale_error) + N(0, depth_noise_m^2); ROP with "
               "N(0, rop_noise^2); zupt = 1 when the tool is stationary; then the true values"
             : "measured depth = true (1 + depth_scale_error) + N(0, depth_noise_m^2); ROP with "
               "N(0, rop_noise^2); zupt = 1 when the tool is stationary; then the true values; "
               "then the auxiliary channels that the aux_sensitivity terms read (their profile "
               "at t, in the channel's units, e.g. degC)"}}}};
  if (timing.clock_offset_s != 0.0 || timing.latency_s > 0.0 || !timing.dropouts.empty()) {
    document["files"]["aids.csv"]["timing"] = fmt::format(
        "rows are sampled at true times k / aid_rate_hz; t = true time + clock_offset_s ({} s); "
        "measured_depth_m, rop_mph and zupt are the readings of true time t_true - latency_s "
        "({} s, from 0 at the start); the *_true columns and the channels are at t_true; no rows "
        "at true times inside the {} dropouts",
        timing.clock_offset_s, timing.latency_s, timing.dropouts.size());
  }
  constexpr double kDegPerHour = std::numbers::pi / 180.0 / 3600.0;
  constexpr double kMilliG = 9.80665e-3;
  nlohmann::json gyro_bias = nlohmann::json::array();
  nlohmann::json accel_bias = nlohmann::json::array();
  for (std::size_t i = 0; i < 3; ++i) {
    gyro_bias.push_back(simulator.gyro_turn_on_bias()[i] / kDegPerHour);
    accel_bias.push_back(simulator.accel_turn_on_bias()[i] / kMilliG);
  }
  document["turn_on_bias"] = {{"gyro_dph", gyro_bias}, {"accel_mg", accel_bias}};
  nlohmann::json scheduled_gyro = nlohmann::json::array();
  nlohmann::json scheduled_accel = nlohmann::json::array();
  for (std::size_t axis = 0; axis < 6; ++axis) {
    (axis < 3 ? scheduled_gyro : scheduled_accel)
        .push_back(to_json(simulator.scheduled_noise_model(axis)));
  }
  document["scheduled_noise_models"] = {
      {"explanation",
       "the scheduled noise as simulated: its terms with a nonstationary term whose segments are "
       "the phases and their noise scales"},
      {"gyro", scheduled_gyro},
      {"accel", scheduled_accel}};
  document["noise_schedule"] = simulator.noise_schedule_json();
  document["motion"] = simulator.motion().describe();
  const double lat = config.site.latitude_rad;
  const Eigen::Vector3d omega_ie = earth_rate_n(lat);
  document["earth"] = {
      {"model", "WGS-84, normal gravity (Somigliana + height correction), no deflection"},
      {"normal_gravity_at_site_mps2", normal_gravity(lat, config.site.height_m)},
      {"earth_rate_n_radps", {omega_ie.x(), omega_ie.y(), omega_ie.z()}}};

  imu.close();
  truth.close();
  aids.close();
  write_pending_file(scenario_json, document.dump(2) + "\n");
  // Everything is complete: move the four files into place.
  imu.commit();
  truth.commit();
  aids.commit();
  scenario_json.commit();
  out_folder.keep();
  ScenarioRunSummary summary;
  summary.epochs = count;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace stochnav

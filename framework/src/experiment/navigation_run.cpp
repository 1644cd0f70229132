#include "stochnav/experiment/navigation_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>

#include "run_files.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/core/progress_bar.hpp"
#include "stochnav/experiment/navigation_files.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/plugin/runtime.hpp"

namespace stochnav {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kRadPerDegPerHour = std::numbers::pi / 180.0 / 3600.0;
constexpr double kTimeMatch_s = 1e-6;

Eigen::Vector3d vector_of(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

FilterOptions filter_options(const plugin::FilterConfig& config) {
  if (config.feedback != plugin::FeedbackMode::kClosedLoop) {
    throw ConfigError(
        "/filter/feedback: open_loop is not implemented by the MWD navigator; use closed_loop");
  }
  const plugin::InitialSigma& s = config.initial_sigma;
  FilterOptions options;
  options.position_sigma_m = vector_of(s.position_m);
  options.velocity_sigma_mps = vector_of(s.velocity_m_s);
  options.attitude_sigma_rad = vector_of(s.attitude_deg) / kDegPerRad;
  options.accel_bias_sigma_mps2 = vector_of(s.accel_bias_m_s2);
  options.gyro_bias_sigma_radps = vector_of(s.gyro_bias_deg_h) * kRadPerDegPerHour;
  return options;
}

// Position, velocity and attitude error of the estimate as the first nine core states.
Eigen::Matrix<double, 9, 1> navigation_error_state(const NavState& estimate,
                                                   const NavState& truth) {
  Eigen::Matrix<double, 9, 1> dx;
  const EarthRadii radii = earth_radii(truth.latitude_rad);
  dx(0) = std::remainder(estimate.longitude_rad - truth.longitude_rad, 2 * std::numbers::pi) *
          (radii.transverse_m + truth.height_m) * std::cos(truth.latitude_rad);
  dx(1) = (estimate.latitude_rad - truth.latitude_rad) * (radii.meridian_m + truth.height_m);
  dx(2) = estimate.height_m - truth.height_m;
  dx.segment<3>(3) = estimate.v_n - truth.v_n;
  const Eigen::AngleAxisd rotation(truth.q_nb * estimate.q_nb.conjugate());
  dx.segment<3>(6) = rotation.angle() * rotation.axis();
  return dx;
}

// Keeps at most about 2 * limit samples, evenly spaced, by doubling the stride when full.
class ThinnedSeries {
 public:
  explicit ThinnedSeries(std::size_t limit) : limit_(std::max<std::size_t>(limit, 2)) {}
  void add(const ErrorSample& sample) {
    if (seen_++ % stride_ != 0) {
      last_ = sample;
      return;
    }
    samples_.push_back(sample);
    last_.reset();
    if (samples_.size() >= 2 * limit_) {
      std::size_t kept = 0;
      for (std::size_t i = 0; i < samples_.size(); i += 2) samples_[kept++] = samples_[i];
      samples_.resize(kept);
      stride_ *= 2;
    }
  }
  std::vector<ErrorSample> take() {
    if (last_) samples_.push_back(*last_);
    return std::move(samples_);
  }

 private:
  std::size_t limit_;
  std::size_t stride_ = 1;
  std::size_t seen_ = 0;
  std::vector<ErrorSample> samples_;
  std::optional<ErrorSample> last_;
};

std::uint64_t estimated_rows(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string chunk(1 << 16, '\0');
  in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
  const auto bytes = static_cast<std::size_t>(in.gcount());
  const auto lines = static_cast<std::size_t>(std::count(chunk.begin(), chunk.begin() +
                                                          static_cast<std::ptrdiff_t>(bytes), '\n'));
  if (lines < 2 || path.extension() == ".gz") return 0;
  return std::filesystem::file_size(path) * lines / bytes;
}

}  // namespace

nlohmann::json NavigationRunResult::metrics_json() const {
  nlohmann::json out;
  out["metrics"] = has_truth ? statistics.to_json() : nlohmann::json(nullptr);
  out["filter_health"] = {{"ok", health.ok()},
                          {"singular_innovations", health.singular_innovations},
                          {"repaired_diagonals", health.repaired_diagonals},
                          {"non_finite", health.non_finite}};
  out["epochs"] = epochs;
  out["duration_s"] = duration_s;
  out["wall_seconds"] = wall_seconds;
  out["noise_models"] = noise_models;
  return out;
}

NavigationRunResult run_navigation(const plugin::RunConfig& config,
                                   const NavigationRunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  const FilterOptions filter = filter_options(config.filter);
  ImuFileReader imu(config.data.imu.string());
  if (!config.data.truth) {
    throw ConfigError("/data: no truth file; stochnav run takes its initial state from truth "
                      "(a simulated scenario or \"truth\": FILE)");
  }
  TruthFileReader truth_reader(config.data.truth->string());
  NavState truth;
  if (!truth_reader.next(truth) || std::abs(truth.t_s - imu.start_time_s()) > kTimeMatch_s) {
    throw InputError(config.data.truth->string() +
                     ": the first truth row must be at the start of the IMU record (t = " +
                     fmt::format("{}", imu.start_time_s()) + " s); write truth from the start");
  }
  const NavState initial = truth;
  bool truth_pending = truth_reader.next(truth);

  const plugin::AidData aid_data =
      config.data.aids ? plugin::read_aid_data(*config.data.aids) : plugin::AidData();
  const plugin::PluginRegistry registry(plugin::default_search_path(config.config_dir));
  plugin::RunPlugins plugins =
      plugin::build_run_plugins(config, registry, aid_data, initial, imu.rate_hz());
  std::vector<plugin::AidPlugin*> aids;
  for (const auto& aid : plugins.aids) aids.push_back(aid.get());
  MwdNavigator navigator(initial, *plugins.gyro, *plugins.accel, aids, filter);

  NavigationRunResult result;
  result.has_truth = true;
  result.noise_models = {{"gyro", plugins.gyro->describe()}, {"accel", plugins.accel->describe()}};
  std::optional<RunFiles> files;
  if (!options.out_dir.empty()) files.emplace(options.out_dir, config.output, plugins.aids);
  ThinnedSeries series(options.series_points);
  ProgressBar progress("run", estimated_rows(config.data.imu), options.progress);

  ImuIncrement increment;
  while (imu.next(increment)) {
    navigator.step(increment);
    ++result.epochs;
    progress.update(result.epochs);
    const bool output_epoch = result.epochs % config.output.decimation == 0;
    if (files) {
      files->write_innovations(navigator.innovations());
      if (output_epoch) files->write_state(navigator);
    }
    while (truth_pending && truth.t_s < increment.t_s - kTimeMatch_s) {
      truth_pending = truth_reader.next(truth);
    }
    if (truth_pending && std::abs(truth.t_s - increment.t_s) <= kTimeMatch_s) {
      const auto errors = navigation_errors(navigator.state(), truth);
      result.statistics.add(errors);
      if (output_epoch) {
        const Eigen::Matrix<double, 9, 9> p = navigator.covariance().topLeftCorner<9, 9>();
        const ErrorSample sample{increment.t_s, errors,
                                 navigation_error_sigmas(navigator.state(), p)};
        series.add(sample);
        if (files) {
          const auto dx = navigation_error_state(navigator.state(), truth);
          files->write_errors(sample, dx.dot(p.ldlt().solve(dx)));
        }
      }
    }
  }
  progress.finish(result.epochs);
  result.health = navigator.health();
  result.duration_s = increment.t_s - imu.start_time_s();
  result.error_series = series.take();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (files) files->commit(result, options.plot);
  return result;
}

}  // namespace stochnav

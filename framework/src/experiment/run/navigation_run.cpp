#include "stochnav/experiment/navigation_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <tuple>

#include "run/run_files.hpp"
#include "run/survey_start.hpp"
#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/core/progress_bar.hpp"
#include "stochnav/experiment/aid_epochs.hpp"
#include "stochnav/experiment/imu_stream.hpp"
#include "stochnav/experiment/initial_state.hpp"
#include "stochnav/experiment/navigation_files.hpp"
#include "stochnav/experiment/run_consistency.hpp"
#include "stochnav/experiment/station_qc.hpp"
#include "stochnav/experiment/streaming_aligner.hpp"
#include "stochnav/experiment/survey.hpp"
#include "stochnav/experiment/survey_error_files.hpp"
#include "stochnav/filter/heading_hypotheses.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/plugin/aid_schedule.hpp"
#include "stochnav/plugin/runtime.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav {
namespace {

constexpr double kTimeMatch_s = plugin::kEpochMatchTolerance_s;
constexpr std::string_view kMeasuredDepthColumn = "measured_depth_m";
// Stationary aid epochs further apart than this (s) are two stationary spans (ZUPTs come at
// about 1 Hz).
constexpr double kMaximumStaticGap_s = 2.5;

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
  const auto lines = static_cast<std::size_t>(
      std::count(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(bytes), '\n'));
  if (lines < 2 || path.extension() == ".gz") return 0;
  return std::filesystem::file_size(path) * lines / bytes;
}

bool is_finite(const NavState& state) {
  return std::isfinite(state.latitude_rad + state.longitude_rad + state.height_m) &&
         state.v_n.allFinite() && state.q_nb.coeffs().allFinite();
}

// A state that became NaN or infinite stays so: rather than a nav.csv of NaN rows with only a
// health flag set, the run fails, saying where.
InputError non_finite_state(const plugin::RunConfig& config, double t_s) {
  return InputError(fmt::format(
      "{}: the navigation solution is not finite from t = {:.9g} s on; the IMU samples near "
      "that time or the noise parameters of the run config are absurd: check both",
      config.data.imu.string(), t_s));
}

// The budget of the station QC: the sensors' bias sigmas before any estimation (the run
// config's initial sigmas, not the alignment's: the check must not lean on the filter it
// checks) with the stationary variance of the noise models' correlated states, their bias
// walk and white-noise PSDs at the start.
StationQcBudget station_qc_budget(const plugin::RunConfig& config, const NavState& site,
                                  plugin::NoiseModelPlugin& gyro, plugin::NoiseModelPlugin& accel,
                                  double t_s) {
  StationQcBudget budget;
  budget.latitude_rad = site.latitude_rad;
  budget.height_m = site.height_m;
  budget.start_t_s = t_s;
  budget.accel_scale_factor_sigma = config.filter.options.accel_scale_factor_sigma;
  Eigen::MatrixXd q(3, 3);
  for (auto [model, initial_sigma, bias_sigma, walk, white] :
       {std::tuple{&gyro, config.filter.options.gyro_bias_sigma_radps,
                   &budget.gyro_bias_sigma_radps, &budget.gyro_bias_walk_psd,
                   &budget.gyro_white_psd},
        std::tuple{&accel, config.filter.options.accel_bias_sigma_mps2,
                   &budget.accel_bias_sigma_mps2, &budget.accel_bias_walk_psd,
                   &budget.accel_white_psd}}) {
    Eigen::Array3d variance = initial_sigma.array().square();
    if (const int size = model->augmented_size(); size > 0) {
      // The stationary variance of the correlated states (a flicker bank) on each axis.
      Eigen::MatrixXd p0(size, size), map(3, size);
      model->augmented_initial_covariance(p0);
      model->augmented_sensor_map(map);
      variance += (map * p0 * map.transpose()).diagonal().array();
    }
    *bias_sigma = variance.sqrt().matrix();
    model->bias_walk_covariance(t_s, 1.0, q);
    *walk = q.diagonal();
    model->white_noise_covariance(t_s, 1.0, q);
    *white = q.diagonal();
  }
  return budget;
}

// The survey QC's verdict into the self-check: a station whose continuous inclination or
// azimuth leaves the connection's static solution by more than 3 combined sigma makes the run's
// self-check optimistic, truth or not.
void add_survey_qc(const std::vector<SurveyStation>& stations, NavigationRunResult& result) {
  std::size_t checked = 0;
  std::size_t flagged = 0;
  double worst_inclination = 0.0;
  double worst_azimuth = 0.0;
  for (const SurveyStation& station : stations) {
    if (!station.qc.checked) continue;
    ++checked;
    flagged += station.qc.flagged ? 1 : 0;
    worst_inclination = std::max(worst_inclination, station.qc.inclination_difference_sigmas);
    if (std::isfinite(station.qc.azimuth_difference_sigmas)) {
      worst_azimuth = std::max(worst_azimuth, station.qc.azimuth_difference_sigmas);
    }
  }
  result.self_check["survey_qc"] = {{"stations", stations.size()},
                                    {"checked", checked},
                                    {"flagged", flagged},
                                    {"worst_inclination_sigmas", worst_inclination},
                                    {"worst_azimuth_sigmas", worst_azimuth}};
  if (flagged == 0) return;
  const std::string reason = fmt::format(
      "survey QC: {} of {} stations off their connection's static solution (inclination up to "
      "{:.1f} sigma, azimuth up to {:.1f} sigma)",
      flagged, checked, worst_inclination, worst_azimuth);
  const std::string previous = result.self_check.value("reason", std::string());
  result.self_check["optimistic"] = true;
  result.self_check["reason"] = previous.empty() ? reason : previous + "; " + reason;
  result.warnings.push_back("warning: " + reason);
}

// The bank over the heading's verdict into the self-check: a run that ends with several heading
// hypotheses, apart, reports the mixture's mean and covariance; with headings tens of degrees apart the errors are not Gaussian (along a circle
// of the drilled length), and a heading in the prior's tail leaves the 3-sigma box in position
// while the azimuth stays about inside (sliding east-west at 74 N: north 4.9 sigma, azimuth 3.1;
// docs/drilling-envelope.md, section 4, fix 6). Not "optimistic", which says the covariance is
// too small: unresolved, with a warning. Resolved: the hypotheses whose headings lie within 2
// of the most probable one's heading sigmas of it, a mixture with one peak (two equal
// Gaussians 2 sigmas apart have one), hold all but 0.27 % of the weight, the 3-sigma box's own
// miss rate. A 160-rpm east-west well kept two hypotheses 0.08 deg apart at a sigma of 0.2 deg,
// which merge only within 0.2 sigma; a mirror bank at 57 N put 99 % of its weight on the mirror,
// 7 sigma from the truth, and 1 % on the truth's side (section 7).
constexpr double kResolvedWeight = 0.9973;
constexpr double kResolvedWithinSigmas = 2.0;

void add_heading_resolution(const HeadingHypotheses& bank, NavigationRunResult& result) {
  if (bank.initial_hypotheses() <= 1 && bank.splits() == 0) return;
  constexpr int kHeading = plugin::core_state::kAttitude + 2;
  const double heading_sigma = std::sqrt(bank.most_probable().covariance()(kHeading, kHeading));
  const double weight_near = bank.weight_within_rad(kResolvedWithinSigmas * heading_sigma);
  const bool resolved = weight_near >= kResolvedWeight;
  result.self_check["heading"] = {{"resolved", resolved},
                                  {"hypotheses", bank.hypotheses()},
                                  {"largest_weight", bank.largest_weight()},
                                  {"weight_near_most_probable", weight_near},
                                  {"span_deg", bank.heading_span_rad() * kDegPerRad}};
  if (resolved) return;
  result.warnings.push_back(fmt::format(
      "warning: the heading is not resolved: {} hypotheses remain, the most probable holds {:.0f} "
      "% of the weight and those within 2 sigma of it {:.0f} %; survey positions and azimuths "
      "are their mixture's mean and covariance, which is not Gaussian (an error may leave the "
      "3-sigma box); rotary drilling away from east-west, or an indexed (multi-position) "
      "gyrocompass station at a connection, resolves it; in a horizontal east-west hole the "
      "heading's mirror (180 deg - azimuth) may stay (docs/drilling-envelope.md)",
      bank.hypotheses(), 100.0 * bank.largest_weight(), 100.0 * weight_near));
}

// A run with aids that never accepted an update navigated on the IMU alone while looking like
// an aided run: it fails, saying why the rows were not used.
InputError no_accepted_update(const plugin::RunConfig& config, const plugin::AidData& data,
                              const AidEpochs& epochs, std::uint64_t navigation_epochs) {
  const nlohmann::json rows = epochs.summary_json();
  const std::string source = config.data.aids ? config.data.aids->string() : "(no aid data)";
  return InputError(fmt::format(
      "{}: no aid update was accepted in {} navigation epochs ({} aid rows: {} applied, {} "
      "before the start, {} after the end; every applied one rejected or unusable); check "
      "that the aid times overlap the IMU record and the aid columns' units, or run without "
      "aids",
      source, navigation_epochs, data.rows(), epochs.applied(), rows["before_start"].get<int>(),
      rows["after_end"].get<int>()));
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
  out["consistency"] = consistency;
  out["self_check"] = self_check;
  out["aids"] = aids;
  out["survey_stations"] = survey_stations;
  out["aid_rows"] = aid_rows;
  out["heading_hypotheses"] = heading_hypotheses;
  const MwdAttitude attitude = mwd_from_quaternion(start.q_nb);
  const auto degrees = [](const Eigen::Vector3d& v, double scale) {
    return std::vector<double>{v.x() * scale, v.y() * scale, v.z() * scale};
  };
  constexpr double kDeg = 180.0 / std::numbers::pi;
  out["initial"] = {
      {"t_s", start.t_s},
      {"latitude_deg", start.latitude_rad * kDeg},
      {"longitude_deg", start.longitude_rad * kDeg},
      {"height_m", start.height_m},
      {"inclination_deg", attitude.inclination_rad * kDeg},
      {"azimuth_deg", attitude.azimuth_rad * kDeg},
      {"toolface_deg", attitude.toolface_rad * kDeg},
      {"attitude_sigma_deg", degrees(filter_options.attitude_sigma_rad, kDeg)},
      {"gyro_bias_deg_h", degrees(filter_options.initial_gyro_bias_radps, kDeg * 3600.0)},
      {"gyro_bias_sigma_deg_h", degrees(filter_options.gyro_bias_sigma_radps, kDeg * 3600.0)},
      {"accel_bias_m_s2", degrees(filter_options.initial_accel_bias_mps2, 1.0)},
      {"accel_bias_sigma_m_s2", degrees(filter_options.accel_bias_sigma_mps2, 1.0)}};
  return out;
}

NavigationRunResult run_navigation(const plugin::RunConfig& config,
                                   const NavigationRunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  plugin::check_run_start(config);
  FilterOptions filter = config.filter.options;
  ImuStream imu =
      options.imu_record ? ImuStream(options.imu_record) : ImuStream(config.data.imu.string());

  std::optional<TruthFileReader> truth_reader;
  NavState truth;
  bool truth_pending = false;
  if (config.data.truth) {
    truth_reader.emplace(config.data.truth->string());
    truth_pending = truth_reader->next(truth);
  }

  // The start: the initial_state section (aligned or given), else truth's first row.
  NavState initial;
  std::optional<StreamingAligner> aligner;
  ImuIncrement increment;
  if (config.initial_state) {
    initial = state_from_initial_config(*config.initial_state, imu.start_time_s());
    if (const auto& alignment = config.initial_state->alignment) {
      aligner.emplace(*alignment, imu.start_time_s());
      while (imu.next(increment) && !aligner->feed(increment)) {
      }
      aligner->check();
      initial.t_s = aligner->end_time_s();
    }
  } else {
    if (!truth_pending || std::abs(truth.t_s - imu.start_time_s()) > kTimeMatch_s) {
      throw InputError(config.data.truth->string() +
                       ": the first truth row must be at the start of the IMU record (t = " +
                       fmt::format("{}", imu.start_time_s()) +
                       " s); write truth from the start, or give \"initial_state\"");
    }
    initial = truth;
  }

  plugin::AidData aid_data =
      config.data.aids ? plugin::read_aid_data(*config.data.aids) : plugin::AidData();
  const bool has_md = aid_data.has(kMeasuredDepthColumn);
  const std::span<const double> tally_md =
      has_md ? aid_data.column(kMeasuredDepthColumn, "/data/aids") : std::span<const double>();
  const std::optional<double> tally_at_start_m = tally_md_at_start_m(aid_data);
  check_tie_on_against_tally(config, tally_at_start_m);
  AidEpochs aid_epochs(aid_data, 1.0 / imu.rate_hz());
  const plugin::PluginRegistry registry(plugin::default_search_path(config.config_dir));
  plugin::RunPlugins plugins =
      plugin::build_run_plugins(config, registry, aid_data, initial, imu.rate_hz());
  const NavState tie_on_state = initial;  // before alignment and the deliberate error
  if (aligner) {
    const AlignedStart aligned = aligner->align(initial, filter, *plugins.gyro, *plugins.accel);
    initial = aligned.state;
    filter = aligned.options;
    aligner.reset();  // the span's epochs are not needed again
  }
  const NavState at_tie_on = initial;  // aligned, before the deliberate error: the tie-on row
  NavigationRunResult result;
  result.start = initial;
  const FilterStart start = filter_start(config, initial, filter);
  initial = start.estimate;
  filter = start.options;
  result.filter_options = filter;

  std::vector<std::string> aid_types;
  std::vector<int> aid_dofs;
  for (const auto& aid : plugins.aids) {
    aid_types.emplace_back(aid->type());
    aid_dofs.push_back(aid->measurement_size());
  }
  // One filter, or a bank over the heading when the start leaves it uncertain by many degrees
  // (filter/heading_hypotheses.hpp); each hypothesis gets its own plugins.
  HeadingHypotheses navigator(
      initial, filter, NavigatorPlugins{plugins.gyro, plugins.accel, plugins.aids}, [&] {
        plugin::RunPlugins more =
            plugin::build_run_plugins(config, registry, aid_data, initial, imu.rate_hz());
        return NavigatorPlugins{more.gyro, more.accel, more.aids};
      });
  result.heading_hypotheses = {{"initial", navigator.initial_hypotheses()}};

  // The survey: tie-on at the start position, its MD and attitude (run/survey_start.hpp).
  const std::span<const double> aid_times = aid_data.time_s();
  const plugin::AidSchedule aid_rows = plugin::AidSchedule::at_rows(aid_times);
  const SurveyTieOn tie_on = survey_tie_on(config, tie_on_state, at_tie_on, tally_at_start_m);
  SurveyRecorder survey(
      tie_on, station_qc_budget(config, tie_on_state, *plugins.gyro, *plugins.accel, initial.t_s),
      stated_depth_sigma(config));
  survey.record_tie_on(at_tie_on, navigator.covariance().topLeftCorner<9, 9>());
  StaticSpan since_aid_epoch;  // raw increments since the last aid epoch
  StaticSpan connection_span;  // of the current stationary span (a connection)
  bool was_stationary = false;
  std::vector<bool> is_zupt;
  for (const auto& type : aid_types) is_zupt.push_back(type == "zupt");

  result.has_truth = truth_reader.has_value();
  result.noise_models = {{"gyro", plugins.gyro->describe()}, {"accel", plugins.accel->describe()}};
  result.fitted = {{"gyro", plugins.gyro->params()}, {"accel", plugins.accel->params()}};
  result.fit_quality = {{"gyro", plugins.gyro->fit_quality()},
                        {"accel", plugins.accel->fit_quality()}};
  RunConsistency consistency(aid_types, aid_dofs);
  std::optional<RunFiles> files;
  if (!options.out_dir.empty()) {
    files.emplace(options.out_dir, config.output, plugins, result.has_truth);
  }
  ThinnedSeries series(options.series_points);
  ProgressBar progress("run", estimated_rows(config.data.imu), options.progress);

  while (imu.next(increment)) {
    aid_epochs.advance_to(increment.t_s);
    navigator.step(increment);
    ++result.epochs;
    if (!is_finite(navigator.state())) throw non_finite_state(config, increment.t_s);
    progress.update(result.epochs);
    const bool output_epoch = result.epochs % config.output.decimation == 0;
    const auto innovations = navigator.innovations();
    if (files) {
      files->write_innovations(innovations);
      if (output_epoch) {
        files->write_state(navigator.state(), navigator.gyro_bias_b(), navigator.accel_bias_b(),
                           navigator.covariance());
        // With several heading hypotheses: the most probable one's (the mixture has the core
        // states only).
        files->write_states(navigator.most_probable());
      }
    }
    since_aid_epoch.add(increment.delta_theta_b, increment.delta_v_b, increment.dt_s);
    while (truth_pending && truth.t_s < increment.t_s - kTimeMatch_s) {
      truth_pending = truth_reader->next(truth);
    }
    const bool truth_now = truth_pending && std::abs(truth.t_s - increment.t_s) <= kTimeMatch_s;
    if (!innovations.empty()) {
      consistency.add_innovations(innovations);
      bool stationary = false;
      for (const InnovationRecord& record : innovations) {
        stationary |= record.accepted && is_zupt[static_cast<std::size_t>(record.aid_index)];
      }
      std::optional<double> md;
      if (has_md) {
        if (const auto row = aid_rows.row_at(increment.t_s)) {
          md = sensor_md_m(config, tally_md[*row]);
        }
      }
      if (stationary) {
        // A span continues across consecutive ZUPT epochs only: an aid that measures only at
        // rest leaves no epoch while the tool drills, which must not join two connections.
        if (was_stationary && since_aid_epoch.duration_s <= kMaximumStaticGap_s) {
          connection_span.add(since_aid_epoch);
        } else {
          connection_span = StaticSpan{};
        }
      }
      was_stationary = stationary;
      since_aid_epoch = StaticSpan{};
      survey.observe(navigator.state(), navigator.covariance().topLeftCorner<9, 9>(), stationary,
                     md, truth_now ? &truth : nullptr, &connection_span);
    }
    if (truth_now) {
      const auto errors = navigation_errors(navigator.state(), truth);
      result.statistics.add(errors);
      if (output_epoch) {
        const Eigen::Matrix<double, 9, 9> p = navigator.covariance().topLeftCorner<9, 9>();
        const ErrorSample sample{increment.t_s, errors,
                                 navigation_error_sigmas(navigator.state(), p)};
        series.add(sample);
        const auto dx = navigation_error_state(navigator.state(), truth);
        const double nees = dx.dot(p.ldlt().solve(dx));
        consistency.add_epoch(sample.errors, sample.sigma, nees);
        if (files) files->write_errors(sample, nees);
      }
    }
  }
  progress.finish(result.epochs);
  aid_epochs.finish();
  if (!plugins.aids.empty() && consistency.accepted_updates() == 0) {
    throw no_accepted_update(config, aid_data, aid_epochs, result.epochs);
  }
  survey.finish();
  result.health = navigator.health();
  result.heading_hypotheses["final"] = navigator.hypotheses();
  result.heading_hypotheses["largest_weight"] = navigator.largest_weight();
  result.heading_hypotheses["splits"] = navigator.splits();
  result.duration_s = increment.t_s - imu.start_time_s();
  result.error_series = series.take();
  result.consistency = consistency.consistency_json();
  result.aids = consistency.aids_json();
  result.consistency_line = consistency.consistency_line();
  result.self_check = consistency.self_check_json();
  result.warnings = consistency.aid_warnings();
  add_survey_qc(survey.stations(), result);
  add_heading_resolution(navigator, result);
  result.survey_stations = survey.stations().size();
  result.aid_rows = aid_epochs.summary_json();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (files) {
    SurveyListingOptions listing;
    listing.vertical_section_azimuth_deg = config.survey.vertical_section_azimuth_deg;
    listing.ellipse_confidence = config.survey.ellipse_confidence;
    listing.datum_elevation_m = config.survey.datum_elevation_m;
    listing.tie_on_tvd_m = config.survey.tie_on_tvd_m;
    listing.sensor_to_bit_m = config.survey.sensor_to_bit_m;
    listing.grid_convergence_deg = config.survey.grid_convergence_deg;
    if (const auto& reference = config.survey.well_reference) {
      listing.map_reference =
          MapReference{reference->easting_m, reference->northing_m, reference->scale_factor};
    }
    listing.length_unit =
        config.survey.length_unit == "ft" ? SurveyLengthUnit::kFoot : SurveyLengthUnit::kMetre;
    const std::optional<SurveyErrorModelRequest> error_model =
        survey_error_model_request(config.survey, tie_on, *plugins.gyro);
    files->commit(result, options.plot, survey, tie_on, listing,
                  error_model ? &*error_model : nullptr);
  }
  return result;
}

}  // namespace stochnav

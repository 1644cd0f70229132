#include "run/run_files.hpp"

#include "run/states_file.hpp"

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <cmath>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/experiment/error_plot.hpp"
#include "stochnav/io/csv_numbers.hpp"
#include "stochnav/report/gnuplot.hpp"

namespace stochnav {
namespace {

constexpr double kDegPerHourPerRadPerSecond = kDegPerRad * 3600.0;

std::string error_header() {
  std::string header = "t";
  for (auto name : kErrorMetricNames) header += fmt::format(",{}", name);
  for (auto name : kErrorMetricNames) header += fmt::format(",{}_sigma", name);
  return header + ",nees";
}

}  // namespace

CsvOutput::CsvOutput(const std::filesystem::path& path, const std::string& header)
    : pending_(path), out_(pending_.open_stream()) {
  buffer_ = header + '\n';
}

void CsvOutput::flush() {
  out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  if (!out_) throw_write_error(pending_.temporary_path(), errno);
  buffer_.clear();
}

void CsvOutput::commit() {
  flush();
  out_.close();
  if (!out_) throw_write_error(pending_.temporary_path(), errno);
  pending_.commit();
}

RunFiles::RunFiles(const std::filesystem::path& out_dir, const plugin::OutputConfig& config,
                   const plugin::RunPlugins& plugins, bool with_truth)
    : folder_(out_dir),
      out_dir_(out_dir),
      config_(config),
      nav_(out_dir / "nav.csv", "t,lat,lon,h,ve,vn,vu,inclination,toolface,azimuth"),
      biases_(out_dir / "biases.csv",
              "t,accel_bias_x,accel_bias_y,accel_bias_z,gyro_bias_x_deg_h,gyro_bias_y_deg_h,"
              "gyro_bias_z_deg_h"),
      innovations_(out_dir / "innovations.csv",
                   "t,aid,type,accepted,nis,z0,z1,z2,z3,z4,z5,sigma0,sigma1,sigma2,sigma3,"
                   "sigma4,sigma5") {
  if (with_truth) errors_ = std::make_unique<CsvOutput>(out_dir / "errors.csv", error_header());
  for (const auto& aid : plugins.aids) aid_types_.emplace_back(aid->type());
  states_ = std::make_unique<StatesFile>(out_dir / "states.csv", plugins.layout, *plugins.gyro,
                                         *plugins.accel);
  if (config.covariance) {
    covariance_ = std::make_unique<CsvOutput>(
        out_dir / "covariance.csv",
        "t,pos_e_m,pos_n_m,pos_u_m,vel_e_mps,vel_n_mps,vel_u_mps,att_e_deg,att_n_deg,att_u_deg,"
        "accel_bias_x,accel_bias_y,accel_bias_z,gyro_bias_x_deg_h,gyro_bias_y_deg_h,"
        "gyro_bias_z_deg_h");
  }
}

// Per-epoch rows are formatted with io/csv_numbers.hpp (std::to_chars): the characters of
// the fmt formats in the comments, in half the time.
void RunFiles::write_state(const NavState& s, const Eigen::Vector3d& gyro_bias_b,
                           const Eigen::Vector3d& accel_bias_b, const Eigen::MatrixXd& p) {
  const MwdAttitude a = mwd_from_quaternion(s.q_nb);
  // {:.3f},{:.9f},{:.9f},{:.4f},{:.6g},{:.6g},{:.6g},{:.6f},{:.6f},{:.6f}
  std::string& nav = nav_.buffer();
  append_fixed(nav, s.t_s, 3);
  nav += ',';
  append_fixed(nav, s.latitude_rad * kDegPerRad, 9);
  nav += ',';
  append_fixed(nav, s.longitude_rad * kDegPerRad, 9);
  nav += ',';
  append_fixed(nav, s.height_m, 4);
  for (int i = 0; i < 3; ++i) {
    nav += ',';
    append_general(nav, s.v_n(i), 6);
  }
  for (double angle_rad : {a.inclination_rad, a.toolface_rad, a.azimuth_rad}) {
    nav += ',';
    append_fixed(nav, angle_rad * kDegPerRad, 6);
  }
  nav += '\n';
  nav_.flush_if_full();
  // {:.3f},{:.6g} x 6
  const Eigen::Vector3d& ba = accel_bias_b;
  const Eigen::Vector3d bg = gyro_bias_b * kDegPerHourPerRadPerSecond;
  std::string& biases = biases_.buffer();
  append_fixed(biases, s.t_s, 3);
  for (const Eigen::Vector3d* bias : {&ba, &bg}) {
    for (int i = 0; i < 3; ++i) {
      biases += ',';
      append_general(biases, (*bias)(i), 6);
    }
  }
  biases += '\n';
  biases_.flush_if_full();
  if (covariance_) {
    // {:.3f},{:.6g} x 15
    std::string& out = covariance_->buffer();
    append_fixed(out, s.t_s, 3);
    for (int i = 0; i < 15; ++i) {
      const double scale = i >= 6 && i < 9    ? kDegPerRad
                           : i >= 12 ? kDegPerHourPerRadPerSecond
                                     : 1.0;
      out += ',';
      append_general(out, std::sqrt(p(i, i)) * scale, 6);
    }
    out += '\n';
    covariance_->flush_if_full();
  }
}

RunFiles::~RunFiles() = default;

void RunFiles::write_states(const MwdNavigator& navigator) { states_->write(navigator); }

void RunFiles::write_innovations(std::span<const InnovationRecord> records) {
  for (const InnovationRecord& r : records) {
    // {:.3f},{},{},{},{:.6g}, then z_i and sigma_i {:.6g} (empty cells past the size)
    std::string& out = innovations_.buffer();
    append_fixed(out, r.t_s, 3);
    out += ',' + std::to_string(r.aid_index) + ',' +
           aid_types_[static_cast<std::size_t>(r.aid_index)] + (r.accepted ? ",1," : ",0,");
    append_general(out, r.nis, 6);
    for (const double* values : {r.innovation, r.innovation_sigma}) {
      for (int i = 0; i < InnovationRecord::kMaxSize; ++i) {
        out += ',';
        if (i < r.size) append_general(out, values[i], 6);
      }
    }
    out += '\n';
  }
  innovations_.flush_if_full();
}

void RunFiles::write_errors(const ErrorSample& sample, double nees) {
  if (!errors_) return;
  // {:.3f}, errors and sigmas {:.6g}, nees {:.6g} or empty
  std::string& out = errors_->buffer();
  append_fixed(out, sample.t_s, 3);
  for (const auto* values : {&sample.errors, &sample.sigma}) {
    for (double e : *values) {
      out += ',';
      append_general(out, e, 6);
    }
  }
  out += ',';
  if (config_.nees) append_general(out, nees, 6);
  out += '\n';
  errors_->flush_if_full();
}

namespace {

// An earlier run's files in the same folder: metrics.json (the completion mark) first, then
// every file a run may write, so that none this run does not write (errors.csv of a run with
// truth, survey.png) stays beside this run's.
void remove_previous_run(const std::filesystem::path& out_dir) {
  static constexpr std::array kRunFiles = {
      "metrics.json", "nav.csv",    "biases.csv",        "innovations.csv",
      "errors.csv",   "errors.png", "covariance.csv",    "survey.csv",
      "survey.png",   "well_path.csv", "survey_errors.csv", "states.csv",
      "trajectory.xml", "iscwsa_covariance.csv", "survey_uncertainty.png", "survey_ft.csv"};
  std::error_code ignored;
  for (const char* name : kRunFiles) std::filesystem::remove(out_dir / name, ignored);
}

}  // namespace

void RunFiles::commit(const NavigationRunResult& result, bool plot, const SurveyRecorder& survey,
                      const SurveyTieOn& tie_on, const SurveyListingOptions& listing,
                      const SurveyErrorModelRequest* error_model) {
  remove_previous_run(out_dir_);
  const std::filesystem::path plot_path = out_dir_ / "errors.png";
  if (plot && result.has_truth && result.error_series.size() > 1) {
    try {
      check_plot_request(plot_path);
      plot_navigation_errors(result.error_series, "navigation errors and 3-sigma bounds",
                             plot_path);
    } catch (const ConfigError&) {
      // gnuplot missing: the run's numbers are still complete; the plot is optional.
    }
  }
  std::vector<std::unique_ptr<PendingFile>> survey_files =
      write_survey_files(survey, tie_on, out_dir_, plot, listing, error_model);
  // metrics.json last: its presence says the run completed.
  nav_.commit();
  biases_.commit();
  innovations_.commit();
  if (errors_) errors_->commit();
  if (covariance_) covariance_->commit();
  states_->commit();
  for (auto& file : survey_files) file->commit();
  write_file_atomically(out_dir_ / "metrics.json", result.metrics_json().dump(2) + "\n");
  folder_.keep();
}

}  // namespace stochnav

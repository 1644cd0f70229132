#pragma once
// The files of one navigation run (experiment/navigation_run.hpp lists them), streamed into
// temporary files and renamed into place together by commit().

#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "stochnav/experiment/navigation_run.hpp"
#include "stochnav/experiment/survey.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/plugin/runtime.hpp"

namespace stochnav {

class StatesFile;

/// A CSV file written through a large buffer into a PendingFile.
class CsvOutput final {
 public:
  CsvOutput(const std::filesystem::path& path, const std::string& header);
  std::string& buffer() { return buffer_; }
  void flush_if_full() {
    if (buffer_.size() > (1u << 20)) flush();
  }
  void flush();
  void commit();

 private:
  PendingFile pending_;
  std::ofstream out_;
  std::string buffer_;
};

class RunFiles final {
 public:
  /// errors.csv only `with_truth`; states.csv with the columns of `plugins`' layout.
  RunFiles(const std::filesystem::path& out_dir, const plugin::OutputConfig& config,
           const plugin::RunPlugins& plugins, bool with_truth);
  ~RunFiles();

  /// One nav.csv, biases.csv (and covariance.csv) row: the estimate, its biases (rad/s,
  /// m/s^2) and the covariance whose first 15 rows and columns are the core states'.
  void write_state(const NavState& s, const Eigen::Vector3d& gyro_bias_b,
                   const Eigen::Vector3d& accel_bias_b, const Eigen::MatrixXd& p);
  /// One states.csv row (run/states_file.hpp): the navigator's sensor-error states and sigmas.
  void write_states(const MwdNavigator& navigator);
  void write_innovations(std::span<const InnovationRecord> records);
  void write_errors(const ErrorSample& sample, double nees);

  /// metrics.json, errors.png (when `plot` and gnuplot is present), the survey files
  /// (experiment/survey.hpp), then every file renamed into place.
  void commit(const NavigationRunResult& result, bool plot, const SurveyRecorder& survey,
              const SurveyTieOn& tie_on, const SurveyListingOptions& listing,
              const SurveyErrorModelRequest* error_model = nullptr);

 private:
  OutputFolder folder_;  // first: created before the files, removed after them on failure
  std::filesystem::path out_dir_;
  plugin::OutputConfig config_;
  std::vector<std::string> aid_types_;
  CsvOutput nav_, biases_, innovations_;
  std::unique_ptr<CsvOutput> errors_;
  std::unique_ptr<CsvOutput> covariance_;
  std::unique_ptr<StatesFile> states_;
};

}  // namespace stochnav

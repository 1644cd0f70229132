#pragma once
// A survey tool model's covariance beside the filter's, for a run's survey stations (the run
// config's "survey/error_model", plugin/run_config.hpp):
//   iscwsa_covariance.csv   the file of `stochnav survey` (survey_error/covariance_csv.hpp) for
//                           the listing of the run's survey stations (md_m, inclination_deg,
//                           azimuth_deg as survey.csv lists them; the first survey station is
//                           the model's tie-on: the listing `stochnav survey --listing
//                           survey.csv` reads)
//   survey_uncertainty.png  per station MD, the filter's horizontal 1-sigma sqrt(NN + EE) and
//                           TVD 1-sigma beside the model's TOTAL (gnuplot; left out without it)

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stochnav/experiment/survey.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/run_config.hpp"
#include "stochnav/survey_error/continuous_gyro.hpp"
#include "stochnav/survey_error/well_parameters.hpp"

namespace stochnav {

/// What a run needs to evaluate its survey error model.
struct SurveyErrorModelRequest {
  std::string model;                       ///< a survey_error::tool_model_names() name
  survey_error::WellParameters well;       ///< the "well" file's, or the tie-on's site
  survey_error::ContinuousGyroTerms gyro;  ///< gyro_ns_ct: the tool constants, OWSG magnitudes
  /// gyro_ns_ct: the model mapped to the magnitudes when the stations are known (T_run is
  /// theirs); absent: the OWSG magnitudes stay.
  std::optional<NoiseModel> gyro_noise;
  double gyrocompass_time_s = 0.0;  ///< T of the mapping (s)
};

/// The request of a run's "survey" section; nullopt for "error_model": "none". The gyro noise
/// model for gyro_ns_ct: "survey/noise_model" when given; else the run's gyro plugin when it has
/// no augmented states and is not time-varying (white, configured or fitted): its x-y white
/// noise and bias walk over 1 s read as N and K (rad/sqrt(s), rad/s/sqrt(s), the mean of the x
/// and y variances); else none (OWSG magnitudes). Without a "well" file the site is the tie-on's
/// latitude with survey_error::WellParameters' defaults (true north).
std::optional<SurveyErrorModelRequest> survey_error_model_request(
    const plugin::SurveyConfig& config, const SurveyTieOn& tie_on,
    const plugin::NoiseModelPlugin& gyro);

/// iscwsa_covariance.csv and, with `plot` and gnuplot, survey_uncertainty.png for `stations`
/// (the survey stations as listed), written into temporary files in out_dir for the caller to
/// commit. Fewer than two stations: the file holds its header only and there is no plot. Throws
/// InputError "/survey/error_model: reason" when the model cannot be evaluated on the stations.
std::vector<std::unique_ptr<PendingFile>> write_survey_error_files(
    const SurveyErrorModelRequest& request, const std::vector<SurveyStation>& stations,
    const std::filesystem::path& out_dir, bool plot);

}  // namespace stochnav

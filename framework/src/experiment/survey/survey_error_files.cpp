#include "stochnav/experiment/survey_error_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/report/gnuplot.hpp"
#include "stochnav/survey_error/covariance_csv.hpp"
#include "stochnav/survey_error/gyro_noise_mapping.hpp"
#include "stochnav/survey_error/tool_models.hpp"

namespace stochnav {
namespace {

/// The white part of a gyro model without augmented states, as a noise model in rad/s: the x-y
/// axes' mean white-noise and bias-walk variances over 1 s.
NoiseModel white_gyro_noise_model(const plugin::NoiseModelPlugin& gyro) {
  Eigen::MatrixXd white = Eigen::MatrixXd::Zero(3, 3);
  Eigen::MatrixXd walk = Eigen::MatrixXd::Zero(3, 3);
  gyro.white_noise_covariance(0.0, 1.0, white);
  gyro.bias_walk_covariance(0.0, 1.0, walk);
  NoiseModel model;
  model.unit = Unit::kRadPerSecond;
  model.rate_hz = 1.0;
  model.terms = {AngleRandomWalkTerm{std::sqrt((white(0, 0) + white(1, 1)) / 2.0)},
                 RateRandomWalkTerm{std::sqrt((walk(0, 0) + walk(1, 1)) / 2.0)}};
  return model;
}

std::vector<survey_error::ListingStation> listing_of(const std::vector<SurveyStation>& stations) {
  std::vector<survey_error::ListingStation> listing;
  for (const SurveyStation& s : stations) {
    listing.push_back({s.md_m, s.inclination_deg * kRadPerDeg, s.azimuth_deg * kRadPerDeg});
  }
  return listing;
}

survey_error::SurveyCovariance model_covariance(const SurveyErrorModelRequest& request,
                                                const std::vector<SurveyStation>& stations) {
  const auto listing = listing_of(stations);
  survey_error::WellParameters well = request.well;
  // DSTG's MD x TVD needs the first station's TVD: the well file's, else its MD (a vertical
  // hole above it; the other sources do not use it).
  if (!well.tie_on_tvd_m) well.tie_on_tvd_m = listing.front().md_m;
  survey_error::ContinuousGyroTerms gyro = request.gyro;
  try {
    if (request.gyro_noise) {
      gyro = survey_error::map_gyro_noise_model(
                 *request.gyro_noise, request.gyrocompass_time_s,
                 survey_error::continuous_run_time_s(listing, request.gyro), request.gyro)
                 .terms;
    }
    return survey_error::tool_model_covariance(request.model, listing, well, gyro);
  } catch (const std::invalid_argument& error) {
    throw InputError(std::string("/survey/error_model: ") + request.model +
                     " cannot be evaluated on the run's survey stations: " + error.what());
  }
}

/// Datablock $sigma: md, filter horizontal, filter TVD, model horizontal, model TVD (m).
std::string sigma_datablock(const std::vector<SurveyStation>& stations,
                            const survey_error::SurveyCovariance& model) {
  std::string block = "$sigma << EOD\n";
  for (std::size_t k = 0; k < stations.size(); ++k) {
    const Eigen::Matrix3d& filter = stations[k].position_covariance_nev_m2;
    const Eigen::Matrix3d& total = model.total_nev_m2[k];
    block += fmt::format(
        "{:.9g} {:.9g} {:.9g} {:.9g} {:.9g}\n", stations[k].md_m,
        std::sqrt(std::max(filter(0, 0) + filter(1, 1), 0.0)), stations[k].tvd_sigma_m,
        std::sqrt(std::max(total(0, 0) + total(1, 1), 0.0)), std::sqrt(std::max(total(2, 2), 0.0)));
  }
  return block + "EOD\n";
}

std::unique_ptr<PendingFile> pending_uncertainty_plot(const std::vector<SurveyStation>& stations,
                                                      const survey_error::SurveyCovariance& model,
                                                      const std::string& title,
                                                      const std::filesystem::path& path) {
  try {
    check_plot_request(path);
  } catch (const ConfigError&) {
    return nullptr;  // gnuplot missing: the numbers are complete without the plot
  }
  std::string script = sigma_datablock(stations, model);
  script += fmt::format(
      "set multiplot layout 1,2 title 'survey uncertainty: filter vs {}' noenhanced\n"
      "set grid\nset key top left noenhanced\nset xlabel 'MD (m)'\n",
      title);
  for (const auto& [name, filter_column, model_column] :
       {std::tuple{"horizontal", 2, 4}, std::tuple{"TVD", 3, 5}}) {
    script += fmt::format(
        "set title '{0} 1-sigma' noenhanced\nset ylabel '{0} 1-sigma (m)'\n"
        "plot $sigma using 1:{1} with linespoints pt 7 ps 0.6 lc rgb '#1f77b4' title 'filter', "
        "$sigma using 1:{2} with linespoints pt 5 ps 0.6 lc rgb '#d62728' title 'error model "
        "TOTAL'\n",
        name, filter_column, model_column);
  }
  script += "unset multiplot\n";
  auto pending = std::make_unique<PendingFile>(path);
  render_gnuplot(script, *pending);
  return pending;
}

}  // namespace

std::optional<SurveyErrorModelRequest> survey_error_model_request(
    const plugin::SurveyConfig& config, const SurveyTieOn& tie_on,
    const plugin::NoiseModelPlugin& gyro) {
  if (config.error_model == "none") return std::nullopt;
  SurveyErrorModelRequest request;
  request.model = config.error_model;
  if (config.well) {
    request.well = *config.well;
  } else {
    request.well.latitude_rad = tie_on.latitude_rad;
  }
  request.gyro = survey_error::owsg_gyro_ns_ct_terms();
  if (config.running_speed_m_h) request.gyro.running_speed_m_s = *config.running_speed_m_h / 3600.0;
  request.gyrocompass_time_s = config.gyrocompass_time_s;
  // Only GYRO-NS-CT's continuous-gyro magnitudes come from a noise model; the stationary gyro
  // models (gyro_ns, gyro_mwd) have OWSG's magnitudes.
  if (request.model != survey_error::kGyroNsCtModelName) return request;
  if (config.gyro_noise_model) {
    request.gyro_noise = config.gyro_noise_model;
  } else if (gyro.augmented_size() == 0 && !gyro.time_varying()) {
    request.gyro_noise = white_gyro_noise_model(gyro);
  }
  return request;
}

std::vector<std::unique_ptr<PendingFile>> write_survey_error_files(
    const SurveyErrorModelRequest& request, const std::vector<SurveyStation>& stations,
    const std::filesystem::path& out_dir, bool plot) {
  std::vector<std::unique_ptr<PendingFile>> files;
  auto csv = std::make_unique<PendingFile>(out_dir / "iscwsa_covariance.csv");
  if (stations.size() < 2) {
    write_pending_file(*csv, std::string(survey_error::kCovarianceCsvHeader) + '\n');
    files.push_back(std::move(csv));
    return files;
  }
  const survey_error::SurveyCovariance model = model_covariance(request, stations);
  write_pending_file(*csv, survey_error::covariance_csv(model));
  files.push_back(std::move(csv));
  if (plot) {
    if (auto picture =
            pending_uncertainty_plot(stations, model, survey_error::tool_model_title(request.model),
                                     out_dir / "survey_uncertainty.png")) {
      files.push_back(std::move(picture));
    }
  }
  return files;
}

}  // namespace stochnav

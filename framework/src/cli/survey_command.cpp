// stochnav survey --listing L.csv --well W.json
//                 --model mwd_rev5|mwd_rev4|gyro_ns_ct|gyro_ns|gyro_mwd
//                 [--noise-model FIT.json] [--gyrocompass-time-s T] [--running-speed-m-h V]
//                 --out DIR
// The position covariance of a survey listing under a survey tool model, per station and error
// source (survey_error/tool_models.hpp), written to DIR/iscwsa_covariance.csv. gyro_ns_ct is the
// whole OWSG GYRO-NS-CT tool model (19 sources); its continuous-gyro magnitudes (GXY-RN, GXY-GD,
// GXY-GRW) are OWSG's or mapped from a fitted gyro noise model
// (survey_error/gyro_noise_mapping.hpp), its other magnitudes OWSG's. gyro_ns and gyro_mwd are
// the OWSG stationary gyrocompass tool models GYRO-NS and GYRO-MWD (18 sources, OWSG magnitudes).

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "command_support.hpp"
#include "commands.hpp"
#include "standard_output.hpp"
#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/survey_error/covariance_csv.hpp"
#include "stochnav/survey_error/gyro_noise_mapping.hpp"
#include "stochnav/survey_error/survey_inputs.hpp"
#include "stochnav/survey_error/tool_models.hpp"

namespace stochnav::cli {
namespace {

struct SurveyArguments {
  std::string listing;
  std::string well;
  std::string model;
  std::string noise_model;                   ///< FIT.json, gyro_ns_ct only
  std::optional<double> gyrocompass_time_s;  ///< with --noise-model only
  std::optional<double> running_speed_m_h;   ///< gyro_ns_ct only
  std::string out;
};

constexpr char kCovarianceFileName[] = "iscwsa_covariance.csv";

/// The last station's total 1-sigma along N, E and V, for the summary line.
std::string deepest_sigmas(const survey_error::SurveyCovariance& covariance) {
  const Eigen::Matrix3d& total = covariance.total_nev_m2.back();
  return fmt::format("at MD {:g} m the total 1-sigma is N {:.3f} m, E {:.3f} m, V {:.3f} m",
                     covariance.md_m.back(), std::sqrt(total(0, 0)), std::sqrt(total(1, 1)),
                     std::sqrt(total(2, 2)));
}

/// The gyro options belong to gyro_ns_ct, T to a noise model: say so instead of ignoring them.
void check_gyro_options(const SurveyArguments& arguments) {
  const bool gyro = arguments.model == survey_error::kGyroNsCtModelName;
  const auto reject = [&](const char* option) {
    throw ConfigError(
        fmt::format("{} applies to --model gyro_ns_ct only (got --model {}); drop "
                    "it or use --model gyro_ns_ct",
                    option, arguments.model));
  };
  if (!gyro && !arguments.noise_model.empty()) reject("--noise-model");
  if (!gyro && arguments.running_speed_m_h) reject("--running-speed-m-h");
  if (!gyro && arguments.gyrocompass_time_s) reject("--gyrocompass-time-s");
  if (arguments.gyrocompass_time_s && arguments.noise_model.empty()) {
    throw ConfigError(
        "--gyrocompass-time-s maps a noise model's angle random walk to GXY-RN; give "
        "--noise-model FIT.json with it, or drop it (the OWSG magnitudes need no time)");
  }
}

/// The continuous-gyro terms: OWSG's, the running speed as given, the magnitudes mapped from
/// the noise model when there is one. `note` gets what the summary should say about them.
/// (GYRO-NS-CT's other sources keep the OWSG magnitudes.)
survey_error::ContinuousGyroTerms gyro_terms(
    const SurveyArguments& arguments, const std::vector<survey_error::ListingStation>& stations,
    std::string& note) {
  survey_error::ContinuousGyroTerms terms = survey_error::owsg_gyro_ns_ct_terms();
  if (arguments.running_speed_m_h) terms.running_speed_m_s = *arguments.running_speed_m_h / 3600.0;
  note = "OWSG magnitudes";  // the continuous-gyro terms'; the other terms are always OWSG's
  if (arguments.noise_model.empty()) return terms;
  const NoiseModel model = survey_error::read_gyro_noise_model(arguments.noise_model);
  const double gyrocompass_s =
      arguments.gyrocompass_time_s.value_or(survey_error::kDefaultGyrocompassTime_s);
  const double run_s = survey_error::continuous_run_time_s(stations, terms);
  const survey_error::MappedGyroTerms mapped =
      survey_error::map_gyro_noise_model(model, gyrocompass_s, run_s, terms);
  note = fmt::format("from {}: gyrocompass {:g} s, continuous run {:.0f} s", arguments.noise_model,
                     gyrocompass_s, run_s);
  for (const std::string& ignored : mapped.ignored_terms) note += "; ignored " + ignored;
  return mapped.terms;
}

std::string describe_gyro_terms(const survey_error::ContinuousGyroTerms& terms) {
  constexpr double kDegPerHourPerRadPerSecond = kDegPerRad * 3600.0;
  return fmt::format(
      "continuous-gyro terms GXY-RN {:.4g} deg/h, GXY-GD {:.4g} deg/h, GXY-GRW {:.4g} "
      "deg/sqrt(h), {:g} m/h (the other terms at the OWSG magnitudes)",
      terms.noise_rad_s * kDegPerHourPerRadPerSecond,
      terms.drift_rad_s * kDegPerHourPerRadPerSecond,
      terms.random_walk_rad_per_sqrt_s * kDegPerRad * 60.0, terms.running_speed_m_s * 3600.0);
}

void run_survey(const SurveyArguments& arguments) {
  survey_error::check_tool_model_name(arguments.model, "--model");
  check_gyro_options(arguments);
  const bool gyro = arguments.model == survey_error::kGyroNsCtModelName;
  const survey_error::WellParameters well = survey_error::read_well_parameters(arguments.well);
  if (survey_error::is_gyro_tool_model(arguments.model)) {
    survey_error::check_well_for_gyro(well, arguments.well);
  }
  const auto stations = survey_error::read_survey_listing(arguments.listing);
  survey_error::check_listing_against_well(stations, well, arguments.well, arguments.listing);
  std::string gyro_note;
  const survey_error::ContinuousGyroTerms terms =
      gyro ? gyro_terms(arguments, stations, gyro_note) : survey_error::ContinuousGyroTerms{};
  survey_error::SurveyCovariance covariance;
  try {
    covariance = survey_error::tool_model_covariance(arguments.model, stations, well, terms);
  } catch (const std::invalid_argument& error) {
    // The listing passed its own checks; what is left is the gyro models' geometry (a
    // gyrocompass station at 90 deg).
    throw InputError(arguments.listing + ": " + error.what());
  }
  const std::string text = survey_error::covariance_csv(covariance);

  OutputFolder out_folder(arguments.out);
  const std::filesystem::path file = out_folder.path() / kCovarianceFileName;
  write_file_atomically(file, text);
  out_folder.keep();
  std::string summary =
      fmt::format("{}: {} stations x {} sources (+ TOTAL); {}\n",
                  survey_error::tool_model_title(arguments.model), stations.size(),
                  covariance.sources.size(), deepest_sigmas(covariance));
  if (gyro) summary += fmt::format("{}; {}\n", describe_gyro_terms(terms), gyro_note);
  write_standard_output(summary + fmt::format("wrote {}\n", file.string()));
}

}  // namespace

void add_survey_command(CLI::App& app) {
  auto arguments = std::make_shared<SurveyArguments>();
  CLI::App* command = app.add_subcommand(
      "survey", "Survey tool error model: position covariance of a survey listing per source");
  command
      ->add_option(
          "--listing", arguments->listing,
          "Survey listing CSV with columns md_m,inclination_deg,azimuth_deg (tie-on first)")
      ->required();
  command
      ->add_option("--well", arguments->well,
                   "Well JSON: field, gravity, azimuth reference (docs/survey-error-model.md)")
      ->required();
  command
      ->add_option("--model", arguments->model,
                   "mwd_rev5 (ISCWSA MWD Rev5.11), mwd_rev4, or an OWSG gyro tool model: "
                   "gyro_ns_ct (GYRO-NS-CT: gyrocompass, then continuous survey), gyro_ns "
                   "(GYRO-NS: gyrocompass at every station), gyro_mwd (GYRO-MWD: gyro while "
                   "drilling)")
      ->required();
  command->add_option("--noise-model", arguments->noise_model,
                      "gyro_ns_ct: the x-y gyros' fitted noise model (stochnav fit JSON) giving "
                      "the continuous-gyro magnitudes GXY-RN, GXY-GD, GXY-GRW (default: OWSG's)");
  command
      ->add_option("--gyrocompass-time-s", arguments->gyrocompass_time_s,
                   fmt::format("gyro_ns_ct with --noise-model: averaging time of one "
                               "gyrocompass measurement (s; default {:g})",
                               survey_error::kDefaultGyrocompassTime_s))
      ->check(positive_number());
  command
      ->add_option("--running-speed-m-h", arguments->running_speed_m_h,
                   "gyro_ns_ct: continuous survey running speed along hole (m/h; default 2743.2)")
      ->check(positive_number());
  command->add_option("--out", arguments->out, "Output folder (iscwsa_covariance.csv)")->required();
  command->callback([arguments] { run_survey(*arguments); });
}

}  // namespace stochnav::cli

// stochnav survey --listing L.csv --well W.json --model mwd_rev5|mwd_rev4 --out DIR: the ISCWSA
// MWD error model's position covariance of a survey listing, per station and error source
// (survey_error/error_propagation.hpp), written to DIR/iscwsa_covariance.csv.

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.hpp"
#include "standard_output.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/survey_error/covariance_csv.hpp"
#include "stochnav/survey_error/error_model.hpp"
#include "stochnav/survey_error/error_propagation.hpp"
#include "stochnav/survey_error/survey_inputs.hpp"

namespace stochnav::cli {
namespace {

struct SurveyArguments {
  std::string listing;
  std::string well;
  std::string model;
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

void run_survey(const SurveyArguments& arguments) {
  const survey_error::SurveyErrorModel& model = survey_error::survey_error_model(arguments.model);
  const survey_error::WellParameters well = survey_error::read_well_parameters(arguments.well);
  const auto stations = survey_error::read_survey_listing(arguments.listing);
  survey_error::check_listing_against_well(stations, well, arguments.well, arguments.listing);
  const survey_error::SurveyCovariance covariance =
      survey_error::propagate_survey_errors(model, stations, well);
  const std::string text = survey_error::covariance_csv(covariance);

  OutputFolder out_folder(arguments.out);
  const std::filesystem::path file = out_folder.path() / kCovarianceFileName;
  write_file_atomically(file, text);
  out_folder.keep();
  write_standard_output(fmt::format("{}: {} stations x {} sources (+ TOTAL); {}\nwrote {}\n",
                                    model.title, stations.size(), model.sources.size(),
                                    deepest_sigmas(covariance), file.string()));
}

}  // namespace

void add_survey_command(CLI::App& app) {
  auto arguments = std::make_shared<SurveyArguments>();
  CLI::App* command = app.add_subcommand(
      "survey", "ISCWSA MWD error model: position covariance of a survey listing per source");
  command
      ->add_option(
          "--listing", arguments->listing,
          "Survey listing CSV with columns md_m,inclination_deg,azimuth_deg (tie-on first)")
      ->required();
  command
      ->add_option("--well", arguments->well,
                   "Well JSON: field, gravity, azimuth reference (docs/survey-error-model.md)")
      ->required();
  command->add_option("--model", arguments->model, "mwd_rev5 (ISCWSA MWD Rev5.11) or mwd_rev4")
      ->required();
  command->add_option("--out", arguments->out, "Output folder (iscwsa_covariance.csv)")->required();
  command->callback([arguments] { run_survey(*arguments); });
}

}  // namespace stochnav::cli

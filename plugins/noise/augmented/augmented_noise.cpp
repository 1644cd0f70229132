// Noise plugin "augmented": a composite noise model per axis (quantization, angle and rate random
// walk, bias instability, rate ramp, Gauss-Markov, sinusoid) turned into equivalent shaping-filter
// states augmented into the filter (model/shaping_filter.hpp says how each term is represented,
// including what is folded into white noise and why quantization is not represented).
//
// params:
//   "model"   one noise model (JSON of model/noise_model_json.hpp) for all three axes, or
//   "models"  [x, y, z]: one per axis. Exactly one of the two. Units of the sensor's quantity
//             (angular rate for gyros, specific force for accelerometers); no nonstationary term.
//   "flicker_band_max_s"            upper end of the bias-instability band (s), default 3600;
//                                    the lower end is the models' sampling interval 1 / rate_hz.
//   "flicker_components_per_decade" bank density, > 0, default 2 (the simulator's bank).
//   "fold_below_s"                  first-order states faster than this (s) become white noise,
//                                    >= 0, default 0.1 (the filter's covariance interval).
// Fit params:
//   "terms"   term names to fit (e.g. ["angle_random_walk", "gauss_markov", "gauss_markov"]:
//             gauss_markov and sinusoid may repeat); default: automatic selection (BIC) among
//             quantization, angle_random_walk, bias_instability, rate_random_walk, rate_ramp,
//             gauss_markov.
//   "method"  "avar" (default) or "gmwm" (needs "terms").
//   "start", "fix", "bound"  steering of the terms' parameters (needs "terms";
//             plugin/fit_steering.hpp), e.g. "fix": {"gauss_markov#2.tau_c": 300}.
//   "flicker_components_per_decade" default 1 (about 5 states over a 10 min record's band);
//   "fold_below_s"                  default 0.1.
// The fitted models (natural units) and the record duration as flicker_band_max_s are written
// back by params(), so the fitted model rebuilds equal.

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_option_names.hpp"
#include "stochnav/model/noise_model_json.hpp"
#include "stochnav/model/sensor_shaping.hpp"
#include "stochnav/plugin/calibration_fit.hpp"
#include "stochnav/plugin/fit_steering.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"
#include "stochnav/plugin/tabulated_noise_model.hpp"

namespace {

using stochnav::NoiseModel;
using stochnav::ShapingFilter;
using stochnav::ShapingOptions;
using stochnav::plugin::SensorGroup;
using Models = std::array<NoiseModel, 3>;

struct AugmentedParams {
  Models models;  ///< per axis, natural units
  double flicker_band_max_s = 3600.0;
  double flicker_components_per_decade = 2.0;
  double fold_below_s = 0.1;
};

using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;

// A noise model for the sensor group, without a nonstationary term.
NoiseModel read_model(const nlohmann::json& json, const std::string& pointer, SensorGroup group) {
  NoiseModel model = stochnav::noise_model_from_json(json, pointer);
  const auto expected = stochnav::plugin::sensor_quantity(group);
  if (stochnav::quantity_of(model.unit) != expected) {
    throw stochnav::ConfigError(
        pointer + "/units: found " + json.at("units").dump() + "; expected " +
        (expected == stochnav::Quantity::kAngularRate ? "an angular-rate unit (deg/h, deg/s, rad/s)"
                                                      : "a specific-force unit (m/s^2, g)"));
  }
  for (std::size_t t = 0; t < model.terms.size(); ++t) {
    if (stochnav::term_type(model.terms[t]) == stochnav::TermType::kNonstationary) {
      throw stochnav::ConfigError(pointer + "/terms/" + std::to_string(t) +
                                  ": found a nonstationary term; expected stationary terms only "
                                  "(the oracle plugin follows a schedule)");
    }
  }
  return model;
}

SensorGroup group_of(stochnav::Quantity quantity) {
  return quantity == stochnav::Quantity::kAngularRate ? SensorGroup::kGyro : SensorGroup::kAccel;
}

// "model" (one noise model for every axis) or "models" ([x, y, z]), in the JSON of
// model/noise_model_json.hpp; params() writes "models".
const stochnav::plugin::ValueCodec<Models> kModelsCodec{
    .read =
        [](stochnav::plugin::ParamReader& reader, stochnav::Quantity quantity) {
          const bool one = reader.has("model"), each = reader.has("models");
          if (one == each) {
            throw stochnav::ConfigError(
                reader.pointer() + ": found " +
                (one ? "both \"model\" and \"models\"" : "neither") +
                "; expected \"model\" (all axes) or \"models\" ([x, y, z])");
          }
          if (one) {
            const NoiseModel model =
                read_model(reader.raw("model"), reader.pointer("model"), group_of(quantity));
            return Models{model, model, model};
          }
          const nlohmann::json& models = reader.raw("models");
          if (!models.is_array() || models.size() != 3) {
            stochnav::plugin::param_table_detail::reject(
                reader.pointer("models"), models, "an array of three noise models [x, y, z]");
          }
          Models read;
          for (std::size_t i = 0; i < 3; ++i) {
            read[i] = read_model(models[i], reader.pointer("models") + "/" + std::to_string(i),
                                 group_of(quantity));
          }
          return read;
        },
    .write =
        [](const Models& models, stochnav::Quantity) {
          nlohmann::json out = nlohmann::json::array();
          for (const NoiseModel& model : models) out.push_back(stochnav::to_json(model));
          return out;
        },
    .describe =
        [](const Models& models, stochnav::Quantity) {
          std::string text = "[";
          const char* axis_names[] = {"x", "y", "z"};
          for (std::size_t i = 0; i < 3; ++i) {
            text += fmt::format("{}{}: {}", i == 0 ? "" : "; ", axis_names[i],
                                stochnav::describe(models[i]));
          }
          return text + "]";
        },
    .equal =
        [](const Models& a, const Models& b, double rel_tol) {
          for (std::size_t i = 0; i < 3; ++i) {
            if (!stochnav::equals(a[i], b[i], rel_tol)) return false;
          }
          return true;
        },
    .form = "a noise model (\"model\", all axes) or three ([x, y, z], \"models\")",
};

const stochnav::plugin::ParamTable<AugmentedParams> kAugmentedTable{
    custom(&AugmentedParams::models, "models", kModelsCodec, "the noise model of each axis"),
    scalar(&AugmentedParams::flicker_band_max_s, "flicker_band_max_s", ParamUnit::fixed("s"),
           Bound::kPositive, 3600.0, "upper end of the bias-instability band"),
    scalar(&AugmentedParams::flicker_components_per_decade, "flicker_components_per_decade",
           ParamUnit::fixed(""), Bound::kPositive, 2.0, "flicker bank density"),
    scalar(&AugmentedParams::fold_below_s, "fold_below_s", ParamUnit::fixed("s"),
           Bound::kNonNegative, 0.1, "first-order states faster than this become white noise"),
};

std::array<ShapingFilter, 3> shaping_filters(const AugmentedParams& params) {
  std::array<ShapingFilter, 3> filters;
  for (std::size_t i = 0; i < 3; ++i) {
    ShapingOptions options;
    options.tau0_s = 1.0 / params.models[i].rate_hz;
    options.flicker_band_max_s = std::max(params.flicker_band_max_s, options.tau0_s);
    options.flicker_components_per_decade = params.flicker_components_per_decade;
    options.fold_below_s = params.fold_below_s;
    filters[i] = stochnav::build_shaping_filter(params.models[i], options);
  }
  return filters;
}

class AugmentedNoise final : public stochnav::plugin::TabulatedNoiseModel<AugmentedParams> {
 public:
  AugmentedNoise(SensorGroup group, const AugmentedParams& params)
      : TabulatedNoiseModel(group, kAugmentedTable, params), shaping_(shaping_filters(params)) {}

  std::string_view type() const override { return "augmented"; }
  int augmented_size() const override { return shaping_.size(); }

  void white_noise_covariance(double, double dt_s,
                              Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    shaping_.white_noise_covariance(dt_s, q_white);
  }
  void bias_walk_covariance(double, double dt_s,
                            Eigen::Ref<Eigen::MatrixXd> q_bias) const override {
    shaping_.bias_walk_covariance(dt_s, q_bias);
  }
  void augmented_transition(double, double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                            Eigen::Ref<Eigen::MatrixXd> q_d) const override {
    shaping_.transition(dt_s, phi, q_d);
  }
  void augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const override {
    shaping_.initial_covariance(p0);
  }
  void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const override {
    shaping_.sensor_map(map);
  }

  // The table's description and the shaping states it gives (derived).
  std::string describe() const override {
    std::string text =
        TabulatedNoiseModel::describe() +
        fmt::format("; {} shaping states (x {}, y {}, z {})", shaping_.size(),
                    shaping_.axis(0).size(), shaping_.axis(1).size(), shaping_.axis(2).size());
    for (int i = 0; i < 3; ++i) {
      if (shaping_.axis(i).quantization > 0.0) {
        return text + "; quantization is not represented: its angle error does not accumulate";
      }
    }
    return text;
  }

 private:
  stochnav::SensorShaping shaping_;
};

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_augmented(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return std::make_unique<AugmentedNoise>(
      context.group, stochnav::plugin::parse_params(kAugmentedTable, json, context));
}

using stochnav::TermType;

struct AugmentedFitOptions {
  std::vector<TermType> terms;  ///< empty: automatic selection
  double flicker_components_per_decade = 1.0;
  double fold_below_s = 0.1;
  stochnav::plugin::TermFitOptions fit;  ///< method, start, fix, bound (need terms)
};

/// "terms": an array of term names, gauss_markov and sinusoid repeatable (parse_fit_terms).
stochnav::plugin::ValueCodec<std::vector<TermType>> fit_terms_codec() {
  stochnav::plugin::ValueCodec<std::vector<TermType>> codec;
  codec.read = [](stochnav::plugin::ParamReader& reader, stochnav::Quantity) {
    if (!reader.has("terms")) return std::vector<TermType>{};
    const nlohmann::json& json = reader.raw("terms");
    const std::string pointer = reader.pointer("terms");
    if (!json.is_array() || json.empty()) {
      stochnav::plugin::param_table_detail::reject(pointer, json,
                                                   "a non-empty array of term names");
    }
    std::vector<std::string> names;
    for (std::size_t i = 0; i < json.size(); ++i) {
      if (!json[i].is_string() || json[i].get<std::string>().empty()) {
        stochnav::plugin::param_table_detail::reject(pointer + "/" + std::to_string(i), json[i],
                                                     "a term name");
      }
      names.push_back(json[i].get<std::string>());
      // An unknown name is refused at its own index.
      stochnav::parse_fit_terms(std::span(&names.back(), 1), pointer + "/" + std::to_string(i));
    }
    return stochnav::parse_fit_terms(names, pointer);
  };
  codec.write = [](const std::vector<TermType>& terms, stochnav::Quantity) {
    nlohmann::json names = nlohmann::json::array();
    for (TermType type : terms) names.push_back(std::string(stochnav::term_type_name(type)));
    return names;
  };
  codec.describe = [](const std::vector<TermType>& terms, stochnav::Quantity q) {
    return fit_terms_codec().write(terms, q).dump();
  };
  codec.equal = [](const std::vector<TermType>& a, const std::vector<TermType>& b, double) {
    return a == b;
  };
  codec.form = "an array of term names (gauss_markov and sinusoid may repeat), default []";
  return codec;
}

const stochnav::plugin::ParamTable<AugmentedFitOptions> kAugmentedFitTable =
    stochnav::plugin::ParamTable<AugmentedFitOptions>{
        stochnav::plugin::custom(&AugmentedFitOptions::terms, "terms", fit_terms_codec(),
                                 "terms to fit; default [] (automatic selection by BIC)"),
        scalar(&AugmentedFitOptions::flicker_components_per_decade, "flicker_components_per_decade",
               ParamUnit::fixed(""), Bound::kPositive, 1.0, "flicker bank density"),
        scalar(&AugmentedFitOptions::fold_below_s, "fold_below_s", ParamUnit::fixed("s"),
               Bound::kNonNegative, 0.1, "first-order states faster than this become white noise"),
    }
        .plus(lift(&AugmentedFitOptions::fit, stochnav::plugin::term_fit_table()));

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_augmented(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  const auto fit = kAugmentedFitTable.parse(json, context.params_pointer);
  stochnav::FitOptions options;
  options.terms = fit.terms;
  if (!fit.fit.steering.empty() && fit.terms.empty()) {
    throw stochnav::ConfigError(context.params_pointer +
                                "/terms: missing; \"start\", \"fix\" and \"bound\" steer the "
                                "terms given: name them (e.g. [\"angle_random_walk\", "
                                "\"gauss_markov\"])");
  }
  options.controls = fit.fit.steering.controls(options.terms, record.group);
  const auto fits = stochnav::plugin::fit_calibration_axes(record, options, fit.fit.method);
  AugmentedParams params;
  for (std::size_t i = 0; i < 3; ++i) params.models[i] = fits[i].model;
  params.flicker_band_max_s = static_cast<double>(record.axes[0].size()) / record.rate_hz;
  params.flicker_components_per_decade = fit.flicker_components_per_decade;
  params.fold_below_s = fit.fold_below_s;
  auto model = std::make_unique<AugmentedNoise>(record.group, params);
  model->set_fit_quality(stochnav::plugin::calibration_fit_quality(fits));
  return model;
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("augmented",
                      "composite noise model as shaping-filter states (Gauss-Markov, flicker bank, "
                      "ramp, sinusoid) plus white noise and bias random walk",
                      make_augmented, fit_augmented)
STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(kAugmentedTable, kAugmentedFitTable)

// Noise plugin "arma": the sensor error averaged over blocks of T seconds as an ARMA(p, q)
// process per axis, in max(p, q + 1) augmented states per axis (Harvey's state-space form); see
// ../arma_common/arma_noise_model.hpp for the model and the factory's params.
//
// Fit params (the calibration record, each axis block-averaged over T and demeaned):
//   "interval_s"  T (s), a whole multiple of the record's sample period. Default 0.1 (the
//                 filter's default covariance interval: keep them equal).
//   "max_p"       largest AR order tried, integer in [0, 3]. Default 3.
//   "max_q"       largest MA order tried, integer in [0, 2]. Default 2.
//   "criterion"   "bic" (default) or "aic": the (p, q), p + q >= 1, minimising it.
//   "K"           rate random walk of the core bias, kept as given (not fitted). Default 0.
// Each candidate is fitted by conditional least squares (model/arma.hpp: Ceres from a
// Hannan-Rissanen start, stationary and invertible by construction).

#include <memory>
#include <stdexcept>

#include "arma_noise_model.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/params.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"

namespace {

namespace an = stochnav::plugin::arma_noise;
using an::Kind;

struct ArmaFitOptions {
  an::ArmaNoiseParams model;  ///< interval_s and K as given; the axes are fitted
  int max_p = 3;
  int max_q = 2;
  stochnav::InformationCriterion criterion = stochnav::InformationCriterion::kBic;
};

const auto kArmaFitTable = lift(&ArmaFitOptions::model, an::constant_params_table())
                               .plus(stochnav::plugin::ParamTable<ArmaFitOptions>{
                                   stochnav::plugin::integer(&ArmaFitOptions::max_p, "max_p", 0, 3,
                                                             3, "largest AR order tried"),
                                   stochnav::plugin::integer(&ArmaFitOptions::max_q, "max_q", 0, 2,
                                                             2, "largest MA order tried"),
                                   an::criterion_entry(&ArmaFitOptions::criterion),
                               });

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_arma(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return an::make_model(Kind::kArma, context.group,
                        an::read_model_params(Kind::kArma, json, context));
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_arma(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  auto options = kArmaFitTable.parse(json, context.params_pointer,
                                     stochnav::plugin::sensor_quantity(record.group));
  const int max_p = options.max_p, max_q = options.max_q;
  if (max_p + max_q < 1) {
    throw stochnav::ConfigError(context.params_pointer +
                                "/max_p: found max_p = max_q = 0; expected max_p + max_q >= 1");
  }
  const auto series =
      an::block_averaged_axes(record, options.model.interval_s, max_p + 10 * (max_p + max_q + 1),
                              context.params_pointer + "/interval_s");
  for (int axis = 0; axis < 3; ++axis) {
    try {
      options.model.axes[axis] =
          stochnav::select_arma(series[axis], max_p, max_q, options.criterion).model;
    } catch (const std::invalid_argument& error) {
      throw stochnav::InputError(record.source + ": cannot fit an ARMA model to axis " +
                                 std::to_string(axis) + ": " + error.what());
    }
  }
  return an::make_model(Kind::kArma, record.group, options.model);
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("arma",
                      "ARMA(p, q) model per axis of the sensor error averaged over the filter's "
                      "covariance interval, as augmented states; conditional ML fit with Ceres, "
                      "orders by BIC/AIC",
                      make_arma, fit_arma)
STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(an::model_table(Kind::kArma), kArmaFitTable)

// Noise plugin "ar": the sensor error averaged over blocks of T seconds as an AR(p) process
// per axis, in p augmented states per axis (companion form); see
// ../arma_common/arma_noise_model.hpp for the state-space model and the factory's params.
//
// Fit params (the calibration record, each axis block-averaged over T and demeaned):
//   "interval_s"  T (s), a whole multiple of the record's sample period. Default 0.1 (the
//                 filter's default covariance interval: keep them equal).
//   "method"      "burg" (default) or "yule_walker".
//   "max_order"   largest order tried, integer in [1, 20]. Default 8.
//   "criterion"   "bic" (default) or "aic": the order p in [1, max_order] minimising it.
//   "K"           rate random walk of the core bias, kept as given (not fitted). Default 0.

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
using stochnav::ArMethod;

struct ArFitOptions {
  an::ArmaNoiseParams model;  ///< interval_s and K as given; the axes are fitted
  ArMethod method = ArMethod::kBurg;
  int max_order = 8;
  stochnav::InformationCriterion criterion = stochnav::InformationCriterion::kBic;
};

const auto kArFitTable =
    lift(&ArFitOptions::model, an::constant_params_table())
        .plus(stochnav::plugin::ParamTable<ArFitOptions>{
            stochnav::plugin::choice(
                &ArFitOptions::method, "method",
                {{"burg", ArMethod::kBurg}, {"yule_walker", ArMethod::kYuleWalker}},
                ArMethod::kBurg, "estimator of the AR coefficients"),
            stochnav::plugin::integer(&ArFitOptions::max_order, "max_order", 1, 20, 8,
                                      "largest order tried"),
            an::criterion_entry(&ArFitOptions::criterion),
        });

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_ar(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return an::make_model(Kind::kAr, context.group, an::read_model_params(Kind::kAr, json, context));
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_ar(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  auto options = kArFitTable.parse(json, context.params_pointer,
                                   stochnav::plugin::sensor_quantity(record.group));
  const auto series =
      an::block_averaged_axes(record, options.model.interval_s, 10 * (options.max_order + 1),
                              context.params_pointer + "/interval_s");
  for (int axis = 0; axis < 3; ++axis) {
    try {
      options.model.axes[axis] =
          stochnav::select_ar(series[axis], options.max_order, options.method, options.criterion)
              .model;
    } catch (const std::invalid_argument& error) {
      throw stochnav::InputError(record.source + ": cannot fit an AR model to axis " +
                                 std::to_string(axis) + ": " + error.what());
    }
  }
  return an::make_model(Kind::kAr, record.group, options.model);
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("ar",
                      "AR(p) model per axis of the sensor error averaged over the filter's "
                      "covariance interval, as augmented states; Burg/Yule-Walker fit, order by "
                      "BIC/AIC",
                      make_ar, fit_ar)
STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(an::model_table(Kind::kAr), kArFitTable)

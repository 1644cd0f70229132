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

namespace {

using stochnav::plugin::arma_noise::Kind;

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_ar(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return stochnav::plugin::arma_noise::make_model(
      Kind::kAr, context.group,
      stochnav::plugin::arma_noise::read_model_params(Kind::kAr, json, context));
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_ar(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  namespace an = stochnav::plugin::arma_noise;
  using stochnav::plugin::Bound;
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  an::ArmaNoiseParams params;
  an::constant_params_table().read(reader, stochnav::plugin::sensor_quantity(record.group), params);
  static constexpr std::string_view kMethods[] = {"burg", "yule_walker"};
  const auto method = reader.choice_or("method", "burg", kMethods) == "burg"
                          ? stochnav::ArMethod::kBurg
                          : stochnav::ArMethod::kYuleWalker;
  const int max_order = an::read_integer_or(reader, "max_order", 8, 1, 20);
  const auto criterion = an::read_criterion(reader);
  reader.finish();
  const auto series = an::block_averaged_axes(record, params.interval_s, 10 * (max_order + 1),
                                              reader.pointer("interval_s"));
  for (int axis = 0; axis < 3; ++axis) {
    try {
      params.axes[axis] = stochnav::select_ar(series[axis], max_order, method, criterion).model;
    } catch (const std::invalid_argument& error) {
      throw stochnav::InputError(record.source + ": cannot fit an AR model to axis " +
                                 std::to_string(axis) + ": " + error.what());
    }
  }
  return an::make_model(Kind::kAr, record.group, params);
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("ar",
                      "AR(p) model per axis of the sensor error averaged over the filter's "
                      "covariance interval, as augmented states; Burg/Yule-Walker fit, order by "
                      "BIC/AIC",
                      make_ar, fit_ar)

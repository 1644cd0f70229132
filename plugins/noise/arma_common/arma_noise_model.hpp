#pragma once
// What the noise plugins "ar" and "arma" share (compiled into each): the model of the sensor
// error averaged over blocks of T seconds as an ARMA process per axis, in augmented states.
//
// The filter holds augmented states constant over its covariance interval (FilterOptions::
// covariance_interval_s, 0.1 s by default) and integrates C M x dt into the attitude error, so
// the state is the sensor error averaged over a block of T = interval_s: set interval_s to the
// filter's covariance interval. Per axis a, with r_a = max(p_a, q_a + 1) states in the
// state-space form of model/arma.hpp (first state = block-mean error, natural units rad/s or
// m/s^2), block diagonal over the axes:
//   augmented_size = r_x + r_y + r_z, M picks the first state of each axis block,
//   P0 = the stationary covariance, Phi = A^k, Qd = sum_{j<k} A^j g g^T A^jT sigma^2 with
//   k = round(dt / T) block steps; dt = 0 gives I and 0.
// A step dt that is not a multiple of T is rounded to whole blocks (documented approximation:
// the filter closes intervals early only when an aid is due; with aids on the T grid every
// interval is a multiple of T). White noise Qw = 0: everything is in the states. Optional
// rate random walk K of the core bias: Qb = K^2 dt.

#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <string_view>

#include "stochnav/model/arma.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/param_table.hpp"
#include "stochnav/plugin/params.hpp"

namespace stochnav::plugin::arma_noise {

/// The two plugin types built on this model.
enum class Kind {
  kAr,    ///< "ar": per-axis params {"ar": [...], "sigma": s}
  kArma,  ///< "arma": per-axis params {"ar": [...], "ma": [...], "sigma": s}
};
std::string_view type_name(Kind kind);

/// The model as a plain struct, natural SI units.
struct ArmaNoiseParams {
  double interval_s = 0.1;        ///< T, block length of the series the models describe (s), > 0
  std::array<ArmaModel, 3> axes;  ///< per body axis; sigma in rad/s (gyro) or m/s^2 (accel)
  std::array<double, 3> k{};  ///< rate random walk of the core bias, rad/s/sqrt(s), m/s^2/sqrt(s)
};

/// The factory's params (reporting units, JSON pointers in errors):
///   {"interval_s": T (s, default 0.1), "axes": [{"ar": [phi..], "ma": [theta..] (arma only,
///    default []), "sigma": innovation std of the block mean (deg/h gyro, m/s/h accel)} x 3],
///    "K": rate random walk (deg/h/sqrt(h), m/s/h/sqrt(h); number or [x, y, z], default 0)}.
/// ConfigError when the AR part of an axis is not stationary, an order is out of range
/// (ar: 1 <= p; r <= kMaxArmaStateSize) or interval_s is not a multiple of the IMU period.
ArmaNoiseParams read_model_params(Kind kind, const nlohmann::json& params,
                                  const NoiseModelContext& context);

/// Number of samples at `rate_hz` in one block of interval_s; ConfigError naming `pointer`
/// when interval_s is not a whole multiple (within 1e-6 relative) of the sample period.
int samples_per_block(double interval_s, double rate_hz, const std::string& pointer);

/// Each axis of the record block-averaged over interval_s and demeaned (natural units).
/// InputError naming record.source when an axis has fewer than `min_blocks` blocks.
std::array<std::vector<double>, 3> block_averaged_axes(const CalibrationRecord& record,
                                                       double interval_s, int min_blocks,
                                                       const std::string& interval_pointer);

/// The constant parameters of both plugins' factories and fitters: "interval_s" (s, default 0.1)
/// and "K" (rate random walk of the core bias, reporting units, default 0).
const ParamTable<ArmaNoiseParams>& constant_params_table();

/// The factory's whole table: constant_params_table() and "axes".
const ParamTable<ArmaNoiseParams>& model_table(Kind kind);

/// "criterion": "bic" (default) | "aic", of a fitter's options.
template <class Options>
ParamEntry<Options> criterion_entry(InformationCriterion Options::*member) {
  return choice(member, "criterion",
                {{"bic", InformationCriterion::kBic}, {"aic", InformationCriterion::kAic}},
                InformationCriterion::kBic, "the candidate order minimising it is chosen");
}

std::unique_ptr<NoiseModelPlugin> make_model(Kind kind, SensorGroup group,
                                             const ArmaNoiseParams& params);

}  // namespace stochnav::plugin::arma_noise

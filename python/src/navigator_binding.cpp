// stochnav.Navigator: the MWD navigation filter of `stochnav run` (filter/mwd_navigator.hpp),
// stepped from Python: the noise-model and aid plugins of a run config loaded by name, the
// increments fed epoch by epoch or in blocks, the state, covariance and innovations read back.

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "bindings.hpp"
#include "json_values.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/aid_epochs.hpp"
#include "stochnav/experiment/initial_state.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/plugin/runtime.hpp"

namespace stochnav::python {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kRadPerSecondPerDegPerHour = std::numbers::pi / 180.0 / 3600.0;

/// Aid data from a dict of equal-length columns (one "t", s) or the path of an aids.csv.
plugin::AidData aid_data_argument(const py::object& aids) {
  if (aids.is_none()) return {};
  if (is_path(aids)) return plugin::read_aid_data(path_from_python(aids));
  if (!py::isinstance<py::dict>(aids)) {
    throw py::value_error("aid_data: expected a dict of columns (one named \"t\", s) or the path "
                          "of an aids.csv");
  }
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  for (const auto& [name, column] : aids.cast<py::dict>()) {
    names.push_back(py::str(name).cast<std::string>());
    const SampleArray values(py::reinterpret_borrow<py::object>(column),
                             "aid_data[\"" + names.back() + "\"]");
    values.check_finite(0);
    columns.emplace_back(values.values().begin(), values.values().end());
  }
  return plugin::AidData("aid_data", std::move(names), std::move(columns));
}

/// Innovation records as columns.
py::dict innovation_columns(const std::vector<InnovationRecord>& records) {
  constexpr auto width = static_cast<py::ssize_t>(InnovationRecord::kMaxSize);
  const auto rows = static_cast<py::ssize_t>(records.size());
  py::array_t<double> innovation({rows, width});
  py::array_t<double> sigma({rows, width});
  for (py::ssize_t r = 0; r < rows; ++r) {
    for (py::ssize_t i = 0; i < width; ++i) {
      const bool used = i < records[static_cast<std::size_t>(r)].size;
      innovation.mutable_at(r, i) =
          used ? records[static_cast<std::size_t>(r)].innovation[i] : std::nan("");
      sigma.mutable_at(r, i) =
          used ? records[static_cast<std::size_t>(r)].innovation_sigma[i] : std::nan("");
    }
  }
  py::dict columns;
  columns["t"] = column_of(records, [](const InnovationRecord& r) { return r.t_s; });
  columns["aid"] = integer_column_of(records, [](const InnovationRecord& r) { return r.aid_index; });
  columns["accepted"] =
      integer_column_of(records, [](const InnovationRecord& r) { return r.accepted ? 1 : 0; })
          .attr("astype")("bool");
  columns["nis"] = column_of(records, [](const InnovationRecord& r) { return r.nis; });
  columns["size"] = integer_column_of(records, [](const InnovationRecord& r) { return r.size; });
  columns["z"] = innovation;
  columns["sigma"] = sigma;
  return columns;
}

class PythonNavigator final {
 public:
  PythonNavigator(const py::object& config, const py::object& aid_data, double imu_rate_hz,
                  double t0_s)
      : aid_data_(std::make_unique<plugin::AidData>(aid_data_argument(aid_data))) {
    if (!(imu_rate_hz > 0.0) || !std::isfinite(imu_rate_hz)) {
      throw ConfigError(fmt::format("imu_rate_hz {:g}: give the IMU's epoch rate in Hz (> 0)",
                                    imu_rate_hz));
    }
    const JsonDocument document = json_document(config, "the run config");
    // The data section, if any, is not read: the increments come from Python.
    const plugin::RunConfig run_config =
        plugin::parse_run_config(document.json, document.folder, plugin::DataConfig{});
    if (!run_config.initial_state || !run_config.initial_state->attitude) {
      throw ConfigError("/initial_state/attitude: missing; a Navigator starts from a known tie-on "
                        "and attitude (stochnav.run aligns from a record's static start)");
    }
    const NavState start = state_from_initial_config(*run_config.initial_state, t0_s);
    const plugin::PluginRegistry registry(plugin::default_search_path(run_config.config_dir));
    plugins_ = plugin::build_run_plugins(run_config, registry, *aid_data_, start, imu_rate_hz);
    const FilterStart filter = filter_start(run_config, start, run_config.filter.options);
    std::vector<plugin::AidPlugin*> aids;
    for (const auto& aid : plugins_.aids) aids.push_back(aid.get());
    navigator_ = std::make_unique<MwdNavigator>(filter.estimate, *plugins_.gyro, *plugins_.accel,
                                                aids, filter.options);
    aid_epochs_ = std::make_unique<AidEpochs>(*aid_data_, 1.0 / imu_rate_hz);
  }

  /// One epoch: increments over (t_s - dt_s, t_s].
  py::dict step(double t_s, double dt_s, const py::object& delta_theta_b,
                const py::object& delta_v_b) {
    ImuIncrement increment{.t_s = t_s, .dt_s = dt_s};
    increment.delta_theta_b = three_vector(delta_theta_b, "delta_theta_b");
    increment.delta_v_b = three_vector(delta_v_b, "delta_v_b");
    check_increment(increment);
    advance(increment);
    return innovation_columns(last_innovations_);
  }

  /// Many epochs: rows of t (N), dt (N or None: from t), delta_theta_b and delta_v_b (N x 3).
  py::dict steps(const py::object& t, const py::object& delta_theta_b,
                 const py::object& delta_v_b, const py::object& dt) {
    const SampleArray times(t, "t");
    times.check_finite(1);
    const std::size_t n = times.values().size();
    const auto dtheta = rows_of_three(delta_theta_b, "delta_theta_b", n);
    const auto dv = rows_of_three(delta_v_b, "delta_v_b", n);
    std::vector<double> intervals;
    if (dt.is_none()) {
      double previous = navigator_->state().t_s;
      for (double time : times.values()) {
        intervals.push_back(time - previous);
        previous = time;
      }
    } else {
      const SampleArray given(dt, "dt");
      if (given.values().size() != n) throw py::value_error("dt: one interval per row of t");
      intervals.assign(given.values().begin(), given.values().end());
    }
    std::vector<InnovationRecord> all;
    {
      py::gil_scoped_release release;
      for (std::size_t k = 0; k < n; ++k) {
        ImuIncrement increment{.t_s = times.values()[k], .dt_s = intervals[k]};
        increment.delta_theta_b = Eigen::Vector3d(dtheta.data() + 3 * k);
        increment.delta_v_b = Eigen::Vector3d(dv.data() + 3 * k);
        check_increment(increment);
        advance(increment);
        all.insert(all.end(), last_innovations_.begin(), last_innovations_.end());
      }
    }
    return innovation_columns(all);
  }

  py::dict state() const {
    const NavState& s = navigator_->state();
    const MwdAttitude attitude = mwd_from_quaternion(s.q_nb);
    py::dict out;
    out["t_s"] = s.t_s;
    out["latitude_deg"] = s.latitude_rad * kDegPerRad;
    out["longitude_deg"] = s.longitude_rad * kDegPerRad;
    out["height_m"] = s.height_m;
    out["v_n"] = to_numpy(std::vector<double>{s.v_n.x(), s.v_n.y(), s.v_n.z()});
    out["q_nb"] = to_numpy(std::vector<double>{s.q_nb.w(), s.q_nb.x(), s.q_nb.y(), s.q_nb.z()});
    out["inclination_deg"] = attitude.inclination_rad * kDegPerRad;
    out["azimuth_deg"] = attitude.azimuth_rad * kDegPerRad;
    out["toolface_deg"] = attitude.toolface_rad * kDegPerRad;
    const Eigen::Vector3d gyro = navigator_->gyro_bias_b() / kRadPerSecondPerDegPerHour;
    const Eigen::Vector3d& accel = navigator_->accel_bias_b();
    out["gyro_bias_deg_h"] = to_numpy(std::vector<double>{gyro.x(), gyro.y(), gyro.z()});
    out["accel_bias_m_s2"] = to_numpy(std::vector<double>{accel.x(), accel.y(), accel.z()});
    return out;
  }

  py::array_t<double> covariance(bool now) const {
    return matrix_copy(now ? navigator_->covariance_now() : navigator_->covariance());
  }

  py::array_t<double> block_estimate(const std::string& name) const {
    const Eigen::VectorXd estimate = navigator_->block_estimate(name);
    return to_numpy(std::vector<double>(estimate.data(), estimate.data() + estimate.size()));
  }

  py::array_t<double> block_covariance(const std::string& name) const {
    return matrix_copy(navigator_->block_covariance(name));
  }

  py::list layout() const {
    py::list blocks;
    for (const auto& block : navigator_->layout().blocks()) {
      blocks.append(py::make_tuple(block.name, block.offset, block.size));
    }
    return blocks;
  }

  py::dict health() const {
    const FilterHealth& h = navigator_->health();
    py::dict out;
    out["ok"] = h.ok();
    out["singular_innovations"] = h.singular_innovations;
    out["repaired_diagonals"] = h.repaired_diagonals;
    out["non_finite"] = h.non_finite;
    return out;
  }

  py::dict noise_models() const {
    py::dict out;
    out["gyro"] = plugins_.gyro->describe();
    out["accel"] = plugins_.accel->describe();
    return out;
  }

  std::uint64_t epochs() const { return epochs_; }
  py::dict innovations() const { return innovation_columns(last_innovations_); }

 private:
  static py::array_t<double> matrix_copy(const Eigen::MatrixXd& p) {
    py::array_t<double> out({static_cast<py::ssize_t>(p.rows()), static_cast<py::ssize_t>(p.cols())});
    for (Eigen::Index r = 0; r < p.rows(); ++r) {
      for (Eigen::Index c = 0; c < p.cols(); ++c) out.mutable_at(r, c) = p(r, c);
    }
    return out;
  }

  static Eigen::Vector3d three_vector(const py::object& object, const std::string& name) {
    const auto values = real_argument(object, name).values;
    if (values.size() != 3) throw py::value_error(name + ": expected 3 values (x, y, z body axes)");
    return Eigen::Vector3d(values[0], values[1], values[2]);
  }

  static std::vector<double> rows_of_three(const py::object& object, const std::string& name,
                                           std::size_t rows) {
    const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
        py::module_::import("numpy").attr("asarray")(object));
    if (!array || array.ndim() != 2 || array.shape(1) != 3 ||
        static_cast<std::size_t>(array.shape(0)) != rows) {
      throw py::value_error(name + ": expected an array of shape (len(t), 3)");
    }
    return std::vector<double>(array.data(), array.data() + array.size());
  }

  void check_increment(const ImuIncrement& increment) const {
    const bool finite = std::isfinite(increment.t_s) && std::isfinite(increment.dt_s) &&
                        increment.delta_theta_b.allFinite() && increment.delta_v_b.allFinite();
    if (!finite || !(increment.dt_s > 0.0) ||
        !(increment.t_s > navigator_->state().t_s)) {
      throw InputError(fmt::format(
          "IMU epoch t = {:.9g} s, dt = {:.9g} s: increments must be finite, dt > 0 and t after "
          "the navigator's time {:.9g} s",
          increment.t_s, increment.dt_s, navigator_->state().t_s));
    }
  }

  void advance(const ImuIncrement& increment) {
    aid_epochs_->advance_to(increment.t_s);
    navigator_->step(increment);
    ++epochs_;
    const auto records = navigator_->innovations();
    last_innovations_.assign(records.begin(), records.end());
  }

  std::unique_ptr<plugin::AidData> aid_data_;  // the aids read it: outlives them
  plugin::RunPlugins plugins_;                 // the navigator refers to them: outlive it
  std::unique_ptr<MwdNavigator> navigator_;
  std::unique_ptr<AidEpochs> aid_epochs_;
  std::vector<InnovationRecord> last_innovations_;
  std::uint64_t epochs_ = 0;
};

constexpr const char* kNavigatorDoc = R"(The MWD navigation filter of `stochnav run`, stepped from Python.

A strapdown INS with a closed-loop error-state Kalman filter: 15 core states (position,
velocity, attitude, accelerometer and gyro biases) plus the noise-model plugins' augmented
states; the aid plugins update it when their data has a measurement at an epoch.

Parameters
----------
config : dict or path
    A run config (configs/runs/*.json, docs/navigation.md): "noise" (gyro and accel plugins
    by name, with params or a "fit" to a calibration record), "aids", "filter",
    "initial_state" with "tie_on" and "attitude" (required here), "initial_error". Its
    "data" section, if any, is not read. Plugins are found in the config's folder (a dict:
    the working folder), $STOCHNAV_PLUGIN_PATH and the installed plugin folder.
aid_data : dict, path or None
    The aids' data: a dict of equal-length columns with "t" (s), e.g. {"t": ...,
    "zupt": ...}, or the path of an aids.csv. Rows are moved to the next IMU epoch as in run.
imu_rate_hz : float
    The IMU's epoch rate (Hz).
t0_s : float
    Time of the initial state (s): the start of the first increment.

Feed increments with step() (one epoch) or steps() (arrays, the GIL released); read state(),
covariance(), block_estimate(), block_covariance(), innovations(), health(), layout(). One Navigator is not for several threads at
once (steps() releases the GIL): give each thread its own.
)";

}  // namespace

void bind_navigator(py::module_& module) {
  py::class_<PythonNavigator>(module, "Navigator", kNavigatorDoc)
      .def(py::init<const py::object&, const py::object&, double, double>(), py::arg("config"),
           py::arg("aid_data") = py::none(), py::arg("imu_rate_hz") = 100.0,
           py::arg("t0_s") = 0.0)
      .def("step", &PythonNavigator::step, py::arg("t_s"), py::arg("dt_s"),
           py::arg("delta_theta_b"), py::arg("delta_v_b"),
           "Advance over one IMU epoch (t_s - dt_s, t_s]: delta_theta_b, the integral of the "
           "body angular rate (rad, 3 values), and delta_v_b, of the specific force (m/s), both "
           "raw (uncompensated), body axes (x toolface mark, z down the hole). Returns this "
           "epoch's innovations (as innovations()).")
      .def("steps", &PythonNavigator::steps, py::arg("t"), py::arg("delta_theta_b"),
           py::arg("delta_v_b"), py::arg("dt") = py::none(),
           "Advance over many epochs: t (N, s, end of each interval), delta_theta_b and "
           "delta_v_b (N x 3, rad and m/s), dt (N, s; default the differences of t from the "
           "navigator's time). Returns every innovation of these epochs (as innovations()).")
      .def("state", &PythonNavigator::state,
           "The estimate: t_s, latitude_deg, longitude_deg, height_m (WGS-84), v_n (ENU, m/s), "
           "q_nb (w, x, y, z: body to ENU), inclination_deg, azimuth_deg, toolface_deg, "
           "gyro_bias_deg_h and accel_bias_m_s2 (body axes).")
      .def("covariance", &PythonNavigator::covariance, py::arg("now") = false,
           "P of the error state (n x n, a copy): dr (ENU, m), dv (ENU, m/s), phi (rad), b_a "
           "(m/s^2), b_g (rad/s), then the blocks of layout(). As of the last covariance "
           "interval or update; now=True propagates the open interval first (as a measurement "
           "epoch does) and gives P at the current epoch.")
      .def("block_estimate", &PythonNavigator::block_estimate, py::arg("name"),
           "The estimate of a sensor-error block of layout() by name (SI units): accel_bias "
           "(m/s^2), gyro_bias (rad/s), gyro_scale_factor, accel_scale_factor, or a noise "
           "model's augmented states (\"gyro.<type>\"). ValueError for a navigation block "
           "(its estimate is state()) or an unknown name.")
      .def("block_covariance", &PythonNavigator::block_covariance, py::arg("name"),
           "The rows and columns of covariance() of block `name` (its units squared).")
      .def("layout", &PythonNavigator::layout,
           "The error state's blocks as (name, offset, size) tuples.")
      .def("innovations", &PythonNavigator::innovations,
           "The last epoch's update attempts as columns: t (s), aid (index in the config's "
           "aids), accepted, nis, size, z and sigma (rows x 6, aid units; NaN beyond size).")
      .def("health", &PythonNavigator::health,
           "Filter health counters: ok, singular_innovations, repaired_diagonals, non_finite.")
      .def("noise_models", &PythonNavigator::noise_models,
           "The gyro and accel noise models' descriptions.")
      .def_property_readonly("epochs", &PythonNavigator::epochs, "epochs stepped so far");
}

}  // namespace stochnav::python

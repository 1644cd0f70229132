#pragma once
// The two motion models behind make_true_motion (private to the scenario domain).

#include <string_view>
#include <vector>

#include "drilling_schedule.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/scenario/true_motion.hpp"
#include "stochnav/scenario/vibration.hpp"
#include "stochnav/scenario/well_path.hpp"

namespace stochnav::scenario_detail {

std::string_view table_motion_name(TableMotion motion);

class VibrationTableMotion final : public TrueMotion {
 public:
  VibrationTableMotion(const ScenarioConfig& config, std::uint64_t seed);
  TruthSample truth(double t_s) override;
  void integrate(double t0_s, double t1_s, Eigen::Vector3d& delta_theta_b,
                 Eigen::Vector3d& delta_v_b) override;
  const std::vector<ScenarioPhase>& phases() const override { return phases_; }
  double duration_s() const override { return duration_s_; }
  nlohmann::json describe() const override;

 private:
  struct TablePhase {
    double start_s = 0.0;
    double end_s = 0.0;
    double start_displacement_m = 0.0;
    TableMotion kind = TableMotion::kStatic;
    SumOfSinusoids vibration;
  };
  struct Displacement {
    double velocity_mps = 0.0;
    double displacement_m = 0.0;
    double integral_from_phase_start_ms = 0.0;
  };
  std::size_t phase_at(double t_s, bool at_end) const;
  Displacement displacement_at(std::size_t phase, double t_s);

  SiteConfig site_;
  Eigen::Matrix3d C_nb_;
  Eigen::Vector3d axis_n_;
  double meridian_plus_h_ = 0.0;
  double transverse_plus_h_cos_ = 0.0;
  Eigen::Vector3d omega_ie_n_;
  double gravity0_ = 0.0;
  double gravity_per_height_ = 0.0;
  Eigen::Vector3d gyro_static_b_, gyro_per_displacement_b_, gyro_per_displacement_integral_b_;
  Eigen::Vector3d accel_static_b_, accel_per_velocity_change_b_, accel_per_displacement_b_,
      accel_per_speed_squared_b_, accel_per_displacement_integral_b_;
  std::vector<TablePhase> table_phases_;
  std::vector<ScenarioPhase> phases_;
  double duration_s_ = 0.0;
  double step_s_ = 0.0;
  mutable std::size_t cursor_ = 0;
  bool cache_valid_ = false;
  std::size_t cache_phase_ = 0;
  double cache_t_s_ = 0.0;
  Displacement cache_;
};

class DrillingMotion final : public TrueMotion {
 public:
  explicit DrillingMotion(const ScenarioConfig& config);
  TruthSample truth(double t_s) override;
  void integrate(double t0_s, double t1_s, Eigen::Vector3d& delta_theta_b,
                 Eigen::Vector3d& delta_v_b) override;
  const std::vector<ScenarioPhase>& phases() const override { return phases_; }
  double duration_s() const override { return config_.duration_s; }
  nlohmann::json describe() const override;

  /// Everything the IMU and the truth need at one instant.
  struct Kinematics {
    double measured_depth_m = 0.0;
    double rop_mps = 0.0;
    double latitude_rad = 0.0;
    double longitude_rad = 0.0;
    double height_m = 0.0;
    Eigen::Vector3d v_n = Eigen::Vector3d::Zero();
    Eigen::Vector3d a_n = Eigen::Vector3d::Zero();
    Eigen::Matrix3d C_nb = Eigen::Matrix3d::Identity();
    Eigen::Vector3d omega_nb_b = Eigen::Vector3d::Zero();
  };
  Kinematics kinematics(double t_s) const;

  /// Earth-model values at one position, shared by the nodes of a quadrature sub-interval:
  /// over 10 ms they change by < 1e-10 relative, and their linear change integrates exactly.
  struct EarthFactors {
    double sin_lat = 0.0;
    double cos_lat = 0.0;
    double height_m = 0.0;
    EarthRadii radii{};
    EarthRadii radii_rate{};
    Eigen::Vector3d omega_ie_n = Eigen::Vector3d::Zero();
    double gravity_mps2 = 0.0;
    double gravity_per_height = 0.0;  ///< d normal_gravity / dh (1/s^2)
  };
  static EarthFactors earth_factors(double latitude_rad, double height_m);
  /// With `earth` the Earth factors are taken from it; without, they are computed at the point
  /// (and copied to `computed` when given).
  Kinematics kinematics(double t_s, const EarthFactors* earth,
                        EarthFactors* computed = nullptr) const;

 private:
  const DrillSegment& segment_at(double t_s) const;
  double local_rate_bound(double t0_s, double t1_s) const;

  DrillingConfig config_;
  SiteConfig site_;
  WellPath path_;
  double meridian0_plus_h_ = 0.0;
  double transverse0_plus_h_cos_ = 0.0;
  DrillSchedule schedule_;
  // Calls f(episode) for the episodes overlapping (t0_s, t1_s) (t0_s == t1_s: active at t0_s),
  // time episodes first, each group in its order.
  template <typename F>
  void for_episodes_in(double t0_s, double t1_s, F&& f) const;

  std::vector<VibrationEpisodeConfig> episodes_;  // by time, then the depth-tied spans
  std::size_t time_episodes_ = 0;                 // how many of episodes_ are by time
  bool episode_groups_disjoint_ = true;           // each group ascending and not overlapping
  std::vector<ScenarioPhase> phases_;
  mutable std::size_t segment_cursor_ = 0;
  std::size_t breakpoint_cursor_ = 0;
};

}  // namespace stochnav::scenario_detail

#pragma once
// Internal to survey_error: a listing's geometry as the weighting functions see it, how an
// error at one station moves the well path, and the covariances that follow from the
// correlation of the errors between stations. The equations are error_propagation.hpp's.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "stochnav/core/minimum_curvature.hpp"

#include "stochnav/survey_error/error_model.hpp"
#include "stochnav/survey_error/error_propagation.hpp"
#include "stochnav/survey_error/weighting_functions.hpp"

namespace stochnav::survey_error {

/// Throws std::invalid_argument "CALLER: reason" for a listing the models cannot use: fewer
/// than two stations, a value not finite, an inclination outside [0, pi], MD not strictly
/// increasing, or a first MD other than 0 without well.tie_on_tvd_m.
void check_listing(std::span<const ListingStation> stations, const WellParameters& well,
                   const char* caller);

/// The stations with true and magnetic azimuths, minimum-curvature TVD from
/// well.tie_on_tvd_m (0 if absent) and their previous station.
std::vector<StationGeometry> station_geometries(std::span<const ListingStation> stations,
                                                const WellParameters& well);

/// The change of the unit hole direction (NEV) that `weights` make at `station`:
/// dI/de dt/dI + sin(I) dA/de h.
Eigen::Vector3d direction_change_nev(const StationGeometry& station, const ErrorWeights& weights);

/// How one unit of an error at a station moves the path: b_k (the leg before) and b_k + a_k.
struct StationEffect {
  Eigen::Vector3d before = Eigen::Vector3d::Zero();
  Eigen::Vector3d before_and_after = Eigen::Vector3d::Zero();
};

/// The effect at station k >= 1 of an error that changes its MD by `depth_change_m` and its
/// hole direction by `direction_change`. `whole_first_leg`: the Rev5 first-leg convention.
StationEffect station_effect(const std::vector<StationGeometry>& geometry, std::size_t k,
                             double depth_change_m, const Eigen::Vector3d& direction_change,
                             LegReach reach, bool whole_first_leg);

/// The effect of a unit azimuth error (1 rad) at every station; zero at the tie-on.
std::vector<StationEffect> unit_azimuth_effects(const std::vector<StationGeometry>& geometry);

/// The covariance at every station of an error of 1-sigma `magnitude` whose effects are
/// `effects`: random (independent per station) or systematic, per-well and global (the same
/// at every station).
std::vector<Eigen::Matrix3d> propagate_effects(const std::vector<StationEffect>& effects,
                                               double magnitude, PropagationMode mode);

/// The covariance at every station of errors that are any linear combination of independent
/// standard normal variables z_m: the error at station k is sum over m of loadings(k, m) z_m
/// in units of `unit_effects` (n x m loadings, n the number of stations). Exact for any
/// correlation between stations (a random walk, an error carried forward).
std::vector<Eigen::Matrix3d> propagate_loadings(const std::vector<StationEffect>& unit_effects,
                                                const Eigen::MatrixXd& loadings);

/// A true-north NEV covariance with its horizontal axes rotated to grid north.
Eigen::Matrix3d true_to_grid(const Eigen::Matrix3d& covariance, double convergence_rad);

}  // namespace stochnav::survey_error

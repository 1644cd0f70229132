#pragma once
// The position covariance of a well's survey stations under an ISCWSA error model, per error
// source and in total (ISCWSA MWD Rev5 document; Williamson, "Accuracy prediction for
// directional measurement while drilling", SPE 67616, 2000).
//
// Frames and units: NEV = north, east, vertical (down), m; covariances m^2. N and E are along
// the listing's azimuth reference: true north, or grid north when the listing is grid (the
// model is evaluated with true azimuths and the horizontal axes then rotated by the
// convergence).
//
// Propagation. Station 0 is the tie-on: its position is taken as exact and it carries no survey
// error, so every covariance there is zero. For a source with magnitude s and weights w_k
// (weighting_functions.hpp) at station k, with unit hole directions t_k, measured-depth steps
// dMD_k = MD_k - MD_(k-1), and the direction change d_k = w_I dt/dI + w_L h of the weights:
//   leg before k  b_k = w_MD (t_(k-1) + t_k) / 2 + dMD_k / 2 d_k       (dMD_k d_k: see below)
//   leg after k   a_k = -w_MD (t_k + t_(k+1)) / 2 + dMD_(k+1) / 2 d_k  (0 at the last station)
// (the derivatives of the balanced-tangential form of a minimum-curvature leg, as the document
// uses), and the error vectors
//   e_k = s (b_k + a_k)   (the station's error moving every station after it)
//   e*_k = s b_k          (the station's error moving itself, at the end of the listing).
// The covariance at station K:
//   random:                          sum_(k<K) e_k e_k^T + e*_K e*_K^T
//   systematic, per-well, global:    E_K E_K^T with E_K = sum_(k<K) e_k + e*_K.
// XCLA and XCLH turn the whole leg before the station (b_k = dMD_k d_k, a_k = 0). Under the Rev5
// convention (SurveyErrorModel::first_station_turns_whole_first_leg) the first station's
// direction term in b_1 is dMD_1 d_1. TVD (for DSTG) is by minimum curvature from the first
// station, starting at WellParameters::tie_on_tvd_m (0 when the listing starts at MD 0).

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "stochnav/survey_error/error_model.hpp"
#include "stochnav/survey_error/well_parameters.hpp"

namespace stochnav::survey_error {

/// One row of a survey listing.
struct ListingStation {
  double md_m = 0.0;             ///< measured depth (m)
  double inclination_rad = 0.0;  ///< [0, pi]
  double azimuth_rad = 0.0;      ///< [0, 2 pi), in the well's azimuth reference
};

/// The covariance of one error source at every station.
struct SourceCovariance {
  std::string code;
  PropagationMode mode = PropagationMode::kSystematic;
  std::vector<Eigen::Matrix3d> nev_m2;  ///< one per station, NEV (m^2)
};

struct SurveyCovariance {
  std::vector<double> md_m;                   ///< the stations' measured depths (m)
  std::vector<SourceCovariance> sources;      ///< in the model's order
  std::vector<Eigen::Matrix3d> total_nev_m2;  ///< the sum over the sources, per station
};

/// The covariances of `stations` under `model`. Requires at least two stations, MD strictly
/// increasing, finite values, inclination in [0, pi], and well.tie_on_tvd_m when the first
/// MD is not 0; throws std::invalid_argument "survey_error::propagate_survey_errors: reason"
/// otherwise (the CLI checks its inputs first, naming the file and line).
SurveyCovariance propagate_survey_errors(const SurveyErrorModel& model,
                                         std::span<const ListingStation> stations,
                                         const WellParameters& well);

/// The NEV covariance (m^2) at every station of azimuth errors correlated in any way between
/// stations: the azimuth error of station k (rad, in the listing's reference) is the sum over m
/// of loadings_rad(k, m) z_m, with independent standard normal z_m (n x M loadings, n the number
/// of stations; the tie-on's row is ignored: it carries no error). Each error moves the path as
/// an ISCWSA station error does (half legs around the station). Random errors are a diagonal
/// of loadings, systematic ones a single column, a random walk a lower triangle. Throws
/// std::invalid_argument as propagate_survey_errors, and for loadings with n rows not matching
/// the listing.
std::vector<Eigen::Matrix3d> correlated_azimuth_error_covariance(
    std::span<const ListingStation> stations, const WellParameters& well,
    const Eigen::MatrixXd& loadings_rad);

}  // namespace stochnav::survey_error

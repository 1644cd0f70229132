#pragma once
// The WGS-84 Earth model used by the scenario simulator and the strapdown INS: ellipsoid
// constants, radii of curvature, normal gravity, Earth rate and transport rate, all in the ENU
// navigation frame n of ins/nav_state.hpp. Latitudes are geodetic (rad), heights are above the
// ellipsoid (m). All functions are pure, cheap (a few sin/cos/sqrt) and never throw.

#include <Eigen/Core>

namespace stochnav {

namespace wgs84 {
inline constexpr double kSemiMajorAxis_m = 6378137.0;                               ///< a (m)
inline constexpr double kFlattening = 1.0 / 298.257223563;                          ///< f
inline constexpr double kEccentricitySquared = kFlattening * (2.0 - kFlattening);   ///< e^2
inline constexpr double kSemiMinorAxis_m = kSemiMajorAxis_m * (1.0 - kFlattening);  ///< b (m)
inline constexpr double kEarthRate_radps = 7.292115e-5;       ///< omega_ie (rad/s)
inline constexpr double kGm_m3ps2 = 3.986004418e14;           ///< GM (m^3/s^2)
inline constexpr double kGravityEquator_mps2 = 9.7803253359;  ///< normal gravity at the equator
inline constexpr double kGravityPole_mps2 = 9.8321849378;     ///< normal gravity at the poles
}  // namespace wgs84

/// Principal radii of curvature of the ellipsoid at a latitude.
struct EarthRadii {
  double meridian_m;    ///< R_M, north-south (meridian) radius (m)
  double transverse_m;  ///< R_N, east-west (prime vertical) radius (m)
};

/// R_M = a (1 - e^2) / (1 - e^2 sin^2 lat)^(3/2), R_N = a / sqrt(1 - e^2 sin^2 lat).
EarthRadii earth_radii(double latitude_rad);

/// Derivatives dR_M/dlat and dR_N/dlat (m/rad), for exact kinematics of the simulator.
EarthRadii earth_radii_derivative(double latitude_rad);

/// Normal gravity magnitude (m/s^2): Somigliana's closed form on the ellipsoid with the
/// second-order height correction of NIMA TR8350.2 (eq. 4-3):
///   g(h) = g0 [1 - 2/a (1 + f + m - 2 f sin^2 lat) h + 3 h^2 / a^2],  m = w^2 a^2 b / GM.
double normal_gravity(double latitude_rad, double height_m);

/// d normal_gravity / d height_m (1/s^2, about -3.086e-6): the derivative of the formula above.
double normal_gravity_height_gradient(double latitude_rad, double height_m);

/// Normal gravity vector in n (ENU): (0, 0, -normal_gravity(latitude, height)) (m/s^2). The
/// deflection of the vertical is neglected everywhere in stochnav.
Eigen::Vector3d gravity_n(double latitude_rad, double height_m);

/// Earth rate in n: omega_ie_n = (0, W cos lat, W sin lat) (rad/s), W = wgs84::kEarthRate_radps.
Eigen::Vector3d earth_rate_n(double latitude_rad);

/// Transport rate (rotation of n relative to e caused by moving over the ellipsoid), ENU:
///   omega_en_n = (-v_N / (R_M + h), v_E / (R_N + h), v_E tan(lat) / (R_N + h))  (rad/s)
/// with v_n = (v_E, v_N, v_U) the velocity relative to Earth (m/s). Singular at the poles.
Eigen::Vector3d transport_rate_n(double latitude_rad, double height_m, const Eigen::Vector3d& v_n);

/// The sine, cosine and tangent of one geodetic latitude (rad), computed once where several of
/// the terms above are evaluated at the same latitude (the strapdown update); the tangent as
/// sin / cos (within 2 ulp of std::tan, at a division's cost instead of a tan call's). The
/// overloads below give bit for bit what the latitude_rad overloads give.
struct LatitudeTrig {
  explicit LatitudeTrig(double latitude_rad);
  double latitude_rad;
  double sin, cos, tan;
};
EarthRadii earth_radii(const LatitudeTrig& latitude);
double normal_gravity(const LatitudeTrig& latitude, double height_m);
Eigen::Vector3d gravity_n(const LatitudeTrig& latitude, double height_m);
Eigen::Vector3d earth_rate_n(const LatitudeTrig& latitude);
Eigen::Vector3d transport_rate_n(const LatitudeTrig& latitude, double height_m,
                                 const Eigen::Vector3d& v_n);
/// The same with the radii already known: `radii` must be earth_radii(latitude) (m).
Eigen::Vector3d transport_rate_n(const LatitudeTrig& latitude, const EarthRadii& radii,
                                 double height_m, const Eigen::Vector3d& v_n);

}  // namespace stochnav

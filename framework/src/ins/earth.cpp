#include "stochnav/ins/earth.hpp"

#include <cmath>

namespace stochnav {

namespace {

// The formulas, written once in terms of the latitude's sine (cosine, tangent): both overloads
// of each function evaluate these.
EarthRadii radii_from_sin(double s) {
  const double w = 1.0 - wgs84::kEccentricitySquared * s * s;
  const double sqrt_w = std::sqrt(w);
  return {wgs84::kSemiMajorAxis_m * (1.0 - wgs84::kEccentricitySquared) / (w * sqrt_w),
          wgs84::kSemiMajorAxis_m / sqrt_w};
}

// Somigliana's normal gravity on the ellipsoid, g0, and the bracket c of its height expansion
// g(h) = g0 (1 - 2 c h / a + 3 h^2 / a^2), for sin^2(latitude) = s2.
struct NormalGravityTerms {
  double g0;
  double c;
};

NormalGravityTerms normal_gravity_terms(double s2) {
  using namespace wgs84;
  const double k =
      (kSemiMinorAxis_m * kGravityPole_mps2) / (kSemiMajorAxis_m * kGravityEquator_mps2) - 1.0;
  const double g0 =
      kGravityEquator_mps2 * (1.0 + k * s2) / std::sqrt(1.0 - kEccentricitySquared * s2);
  const double m = kEarthRate_radps * kEarthRate_radps * kSemiMajorAxis_m * kSemiMajorAxis_m *
                   kSemiMinorAxis_m / kGm_m3ps2;
  return {g0, 1.0 + kFlattening + m - 2.0 * kFlattening * s2};
}

double gravity_from_sin_squared(double s2, double height_m) {
  const NormalGravityTerms terms = normal_gravity_terms(s2);
  const double a = wgs84::kSemiMajorAxis_m;
  return terms.g0 * (1.0 - 2.0 / a * terms.c * height_m + 3.0 * height_m * height_m / (a * a));
}

Eigen::Vector3d transport_from(const EarthRadii& r, double tan_lat, double height_m,
                               const Eigen::Vector3d& v_n) {
  const double rn_h = r.transverse_m + height_m;
  return {-v_n.y() / (r.meridian_m + height_m), v_n.x() / rn_h, v_n.x() * tan_lat / rn_h};
}

}  // namespace

EarthRadii earth_radii(double latitude_rad) { return radii_from_sin(std::sin(latitude_rad)); }

EarthRadii earth_radii_derivative(double latitude_rad) {
  const double s = std::sin(latitude_rad);
  const double c = std::cos(latitude_rad);
  const double e2 = wgs84::kEccentricitySquared;
  const double a = wgs84::kSemiMajorAxis_m;
  const double w = 1.0 - e2 * s * s;
  const double sqrt_w = std::sqrt(w);
  // d/dlat w^(-k/2) = k e^2 s c w^(-k/2 - 1).
  return {3.0 * a * (1.0 - e2) * e2 * s * c / (w * w * sqrt_w), a * e2 * s * c / (w * sqrt_w)};
}

double normal_gravity(double latitude_rad, double height_m) {
  const double s = std::sin(latitude_rad);
  return gravity_from_sin_squared(s * s, height_m);
}

double normal_gravity_height_gradient(double latitude_rad, double height_m) {
  const double s = std::sin(latitude_rad);
  const NormalGravityTerms terms = normal_gravity_terms(s * s);
  const double a = wgs84::kSemiMajorAxis_m;
  return terms.g0 * (-2.0 / a * terms.c + 6.0 * height_m / (a * a));
}

Eigen::Vector3d gravity_n(double latitude_rad, double height_m) {
  return {0.0, 0.0, -normal_gravity(latitude_rad, height_m)};
}

Eigen::Vector3d earth_rate_n(double latitude_rad) {
  return {0.0, wgs84::kEarthRate_radps * std::cos(latitude_rad),
          wgs84::kEarthRate_radps * std::sin(latitude_rad)};
}

Eigen::Vector3d transport_rate_n(double latitude_rad, double height_m, const Eigen::Vector3d& v_n) {
  return transport_rate_n(LatitudeTrig(latitude_rad), height_m, v_n);
}

LatitudeTrig::LatitudeTrig(double latitude)
    : latitude_rad(latitude),
      sin(std::sin(latitude)),
      cos(std::cos(latitude)),
      tan(this->sin / this->cos) {}

EarthRadii earth_radii(const LatitudeTrig& latitude) { return radii_from_sin(latitude.sin); }

double normal_gravity(const LatitudeTrig& latitude, double height_m) {
  return gravity_from_sin_squared(latitude.sin * latitude.sin, height_m);
}

Eigen::Vector3d gravity_n(const LatitudeTrig& latitude, double height_m) {
  return {0.0, 0.0, -normal_gravity(latitude, height_m)};
}

Eigen::Vector3d earth_rate_n(const LatitudeTrig& latitude) {
  return {0.0, wgs84::kEarthRate_radps * latitude.cos, wgs84::kEarthRate_radps * latitude.sin};
}

Eigen::Vector3d transport_rate_n(const LatitudeTrig& latitude, double height_m,
                                 const Eigen::Vector3d& v_n) {
  return transport_from(earth_radii(latitude), latitude.tan, height_m, v_n);
}

Eigen::Vector3d transport_rate_n(const LatitudeTrig& latitude, const EarthRadii& radii,
                                 double height_m, const Eigen::Vector3d& v_n) {
  return transport_from(radii, latitude.tan, height_m, v_n);
}

}  // namespace stochnav

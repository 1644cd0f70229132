#pragma once
// The latitude-dependent terms of the Earth model (ins/earth.hpp) at one geodetic latitude
// (rad): its sine, cosine and tangent and the radii of curvature, computed together, and a memo
// that keeps the terms of the last latitude asked for.
//
// Why a memo: at every 100-Hz epoch the strapdown update, the navigator's reference trajectory
// and the error dynamics evaluate these terms at a few latitudes that repeat. The state's
// latitude at an epoch's end is the next epoch's starting latitude, and the strapdown's first
// and refined mid-interval latitudes agree to the last bit unless the radius of curvature
// changes within the epoch by more than a rounding error (a tool moving millimetres per second
// changes its latitude by about 1e-10 rad per epoch). The memo compares the latitude's bits, so
// what it returns is bit for bit LatitudeTerms(latitude_rad): a saving, never a
// different result.

#include <bit>
#include <cstdint>
#include <limits>

#include "stochnav/ins/earth.hpp"

namespace stochnav {

/// The sine, cosine, tangent and radii of curvature of one geodetic latitude (rad).
struct LatitudeTerms {
  explicit LatitudeTerms(double latitude_rad) : trig(latitude_rad), radii(earth_radii(trig)) {}
  LatitudeTrig trig;
  EarthRadii radii;  ///< earth_radii(trig) (m)
};

/// LatitudeTerms of the latitude last asked for, recomputed only when the latitude's bits differ.
class LatitudeTermsMemo {
 public:
  /// The terms of latitude_rad (rad). The reference stays valid until the next call.
  const LatitudeTerms& at(double latitude_rad) {
    if (std::bit_cast<std::uint64_t>(latitude_rad) != std::bit_cast<std::uint64_t>(key_)) {
      terms_ = LatitudeTerms(latitude_rad);
      key_ = latitude_rad;
    }
    return terms_;
  }

 private:
  double key_ = std::numeric_limits<double>::quiet_NaN();
  LatitudeTerms terms_{std::numeric_limits<double>::quiet_NaN()};
};

}  // namespace stochnav

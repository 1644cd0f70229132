#pragma once
// IEEE 952 (Annex C) graphical read-offs of the noise coefficients from an Allan-deviation
// curve: the cross-check printed beside the least-squares fit, and its starting values.
//
// For a term whose deviation grows as tau^mu, the read-off is the lowest straight line of slope mu
// (log-log) through a measured point, read at the tau where that term's deviation equals its
// coefficient:
//   Q  slope -1,   read at tau = sqrt(3) s:  Q = min_i adev_i tau_i / sqrt(3)
//   N  slope -1/2, read at tau = 1 s:        N = min_i adev_i sqrt(tau_i)
//   B  slope 0,    the floor / 0.664:        B = min_i adev_i / sqrt(2 ln 2 / pi)
//   K  slope +1/2, read at tau = 3 s:        K = min_i adev_i sqrt(3 / tau_i)
//   R  slope +1,   read at tau = sqrt(2) s:  R = min_i adev_i sqrt(2) / tau_i
// Because each term's deviation is below the total, every read-off is an upper bound of its
// coefficient, close to it where that term dominates the curve.

#include "stochnav/fit/fit_data.hpp"

namespace stochnav {

struct SlopeReadoff {
  double value = 0.0;  ///< coefficient in natural units (model/noise_term.hpp)
  double tau_s = 0.0;  ///< measured tau where the line touches the curve (s)
};

struct SlopeReadoffs {
  SlopeReadoff quantization;
  SlopeReadoff angle_random_walk;
  SlopeReadoff bias_instability;
  SlopeReadoff rate_random_walk;
  SlopeReadoff rate_ramp;
};

/// Read-offs of a validated FitData (see validate()).
SlopeReadoffs slope_readoffs(const FitData& data);

}  // namespace stochnav

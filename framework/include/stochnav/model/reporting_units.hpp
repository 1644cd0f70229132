#pragma once
// The one place where noise-term coefficients change units: natural SI units of the signal
// (what NoiseTerm holds) <-> the IEEE 952 reporting units of DESIGN.md (what JSON carries).
//
// The reporting units depend only on what the signal measures, never on the unit the signal is
// written in: a gyro model in deg/s still reports N in deg/sqrt(h).
//
// | dimension          | angular rate   | specific force   | plain            |
// |--------------------|----------------|------------------|------------------|
// | angle (Q)          | arcsec         | m/s              | signal*s         |
// | angle/sqrt(time) N | deg/sqrt(h)    | m/s/sqrt(h)      | signal*sqrt(s)   |
// | rate (B, sigma, A) | deg/h          | m/s/h            | signal           |
// | rate/sqrt(time) K  | deg/h/sqrt(h)  | m/s/h/sqrt(h)    | signal/sqrt(s)   |
// | rate/time (R)      | deg/h^2        | m/s/h^2          | signal/s         |
// | time, frequency, phase: s, Hz, rad for every quantity                        |
//
// Angle quantization of an accelerometer is reported in m/s: arcsec has no velocity analogue.
// Check (gyro): sigma_deg/h^2 = (60 N_deg/sqrt(h))^2 / tau, i.e. sigma^2 = N_natural^2 / tau.

#include <string>

#include "stochnav/core/units.hpp"
#include "stochnav/model/noise_term.hpp"

namespace stochnav {

/// Factor f with value_natural = f * value_reported for a parameter of `dimension` on a signal
/// measuring `quantity`.
double natural_per_reported(Quantity quantity, ParameterDimension dimension);

/// Name of the reporting unit, e.g. "deg/sqrt(h)", "m/s/h", "signal/sqrt(s)", "s".
std::string reported_unit_name(Quantity quantity, ParameterDimension dimension);

/// value_natural / natural_per_reported.
double to_reported(Quantity quantity, ParameterDimension dimension, double value_natural);

/// value_reported * natural_per_reported.
double to_natural(Quantity quantity, ParameterDimension dimension, double value_reported);

}  // namespace stochnav

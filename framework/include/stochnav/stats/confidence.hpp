#pragma once
// Chi-square confidence interval of a deviation (NIST SP 1065, Eq. 45; as Stable32 reports it).

namespace stochnav {

/// Stable32's "Confidence Factor = 0.683" (about one standard deviation of a Gaussian).
inline constexpr double kStable32Confidence = 0.683;

/// [lower, upper] bounds of a deviation, in the deviation's unit.
struct DeviationInterval {
  double lower = 0.0;
  double upper = 0.0;
};

/// The two-sided interval holding the true deviation with probability `confidence`, for an
/// estimate `deviation` whose variance has `edf` equivalent degrees of freedom:
///   lower = deviation * sqrt(edf / chi2_inv((1 + confidence) / 2, edf)),
///   upper = deviation * sqrt(edf / chi2_inv((1 - confidence) / 2, edf)).
/// Requires edf > 0 and 0 < confidence < 1; otherwise (NaN included) both bounds are NaN.
DeviationInterval chi_square_interval(double deviation, double edf,
                                      double confidence = kStable32Confidence);

}  // namespace stochnav

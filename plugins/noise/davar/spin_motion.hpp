#pragma once
// A spinning tool's own motion, removed from its two gyro axes across the spin axis before the
// windowed Allan-variance fit (plugin "davar", fit param "spin_axis").
//
// Why: a tool spinning about one body axis (an MWD tool at 60 rpm about z) sees every steady
// angular rate of its surroundings across that axis (Earth rate, about 10 deg/h horizontally at
// 46 deg N; the well's build and turn) as a sinusoid at the spin frequency: 10 deg/h at 1 Hz
// against an angle random walk whose 1-s deviation is a few hundredths of a deg/h. The window fit
// of the raw rate has no term for it; its non-negative fit drops N to zero and the filter gets a
// process noise far below the truth.
//
// Model of the two cross-axis rates (a, b) over one window, phi(t) the spin angle (the integral
// of the spin-axis rate from the window's first sample):
//   [a; b](t) = R(-phi(t)) e + c + noise,   R(phi) = [cos phi, -sin phi; sin phi, cos phi],
// e the steady rate across the spin axis in axes that do not spin (2 unknowns) and c the sensor's
// own bias in body axes (2 unknowns), both constant over a window (minutes). While the tool spins
// they are separable; while it does not, only their sum matters and the residual is the same.
// The 4 unknowns are fitted by least squares to the window's own samples, nothing outside it (a
// causal window stays causal), and the window's Allan deviations are those of the residual.
// Removing 4 parameters from a window of W samples lowers a white noise's Allan variance by a
// fraction of about 4 / W (W = 6000 for 60 s at 100 Hz).
//
// A swing about one spin-free direction (a curved hole vibrating along its axis) is set aside by
// reading the noise on the perpendicular direction (SpinFreeWindow::quiet). Not removed: ramps of
// the spin rate on the spin axis itself and motion in more than one spin-free direction; they
// still read as noise (a larger Q than the sensor's, the conservative side).

#include <array>
#include <cstddef>
#include <numbers>
#include <span>
#include <vector>

namespace stochnav::davar_noise {

/// Body axes across `spin_axis` (0 x, 1 y, 2 z) in right-handed order: z -> (x, y),
/// x -> (y, z), y -> (z, x).
std::array<std::size_t, 2> cross_axes(std::size_t spin_axis);

/// Turns of the spin within a window from which it counts as spinning: its cross axes' noise
/// is then the same in every spin-free direction (below).
inline constexpr double kMinimumTurns = 10.0;

/// Ratio of the spin-free residual's largest to smallest variance from which a spinning window
/// is taken to swing about a fixed spin-free direction. Windows of the 36-h drilling scenario
/// without a swing stay below 4 (1.05 typically, up to 3.7 where the window holds a spin-up);
/// with the 3 g / 8 Hz swing in the build they exceed 5000. A weaker swing is left in (a larger
/// Q, the conservative side).
inline constexpr double kSwingAnisotropy = 10.0;

/// One window of the two cross axes with the steady motion removed.
struct SpinFreeWindow {
  /// Body-axis rates minus the fitted R(-phi) e + c (rad/s).
  std::array<std::vector<double>, 2> residual;
  /// Spin angle covered by the window, in turns (>= 0).
  double turns = 0.0;
  /// When spinning (turns >= kMinimumTurns): largest over smallest eigenvalue of the 2 x 2
  /// covariance of the residual in spin-free axes, R(phi) residual; 1 otherwise.
  double anisotropy = 1.0;
  /// When spinning and anisotropy >= kSwingAnisotropy: the residual in spin-free axes along its
  /// direction of least variance (rad/s); empty otherwise. While the tool spins, each body axis'
  /// noise turns with it, so the sensor's noise is the same in every spin-free direction (the
  /// mean of the two axes' PSDs); a direction that carries far more is carrying motion: an axial
  /// vibration along a curved hole swings the tool about the hole's binormal, a fixed spin-free
  /// direction (210 deg/h at 8 Hz for 3 g along a 3 deg/30 m build). Both cross axes then take
  /// this direction's level. Without a swing each axis keeps its body-axis residual: there a
  /// FOG's flicker floor (a slow bias wander in body axes) stays a floor, where in spin-free axes
  /// it would be moved to the spin frequency and no longer fit the window's N + B model.
  std::vector<double> quiet;
  /// Largest minus smallest 1-s mean of the spin-axis rate over the window (rad/s).
  double spin_rate_range = 0.0;
};

/// The model above fitted to one window and removed. first, second and spin_rate (rad/s) have
/// the same length; rate_hz > 0.
SpinFreeWindow spin_free_window(std::span<const double> first, std::span<const double> second,
                                std::span<const double> spin_rate, double rate_hz);

/// Largest range of a window's 1-s means of the spin-axis rate for which that axis' own Allan
/// deviations are read as its noise: 5 deg/h (rad/s). A 60-rpm spin changing by more than that
/// within a window (the ramps at connections, stick-slip) is motion the axis cannot tell from its
/// noise (a ramp of 5 deg/h per minute already has an Allan variance at 1 s of a FOG's floor).
inline constexpr double kSteadySpinRange = 5.0 / 3600.0 * std::numbers::pi / 180.0;

/// What the cross and spin axes' windows carry once the spin motion is set aside.
struct SpinWindowDeviations {
  /// Overlapping Allan deviations of the two cross axes, [cross axis][window][factor]: of the
  /// quiet direction for both when the window swings, else of each axis' residual.
  std::array<std::vector<std::vector<double>>, 2> cross;
  std::vector<char> spinning;     ///< per window: turned at least kMinimumTurns
  std::vector<char> steady_spin;  ///< per window: spin-axis 1-s means within kSteadySpinRange
};

/// SpinWindowDeviations of every DAVAR window (window k covers samples [k step, k step +
/// window), as in stats/davar.hpp) at the averaging factors `m_values`. Windows are spread over
/// the stats threads; the result does not depend on their number.
SpinWindowDeviations spin_free_window_deviations(std::span<const double> first,
                                                 std::span<const double> second,
                                                 std::span<const double> spin_rate, double rate_hz,
                                                 std::size_t window, std::size_t step,
                                                 std::span<const std::size_t> m_values);

/// The spin axis' own rows (`spin_rows`, [window][factor]) where its rate was not steady are
/// replaced: when the window spins, by the cross axes' common level (the root mean square of
/// their two rows; the triad's axes share one noise level: an assumption, stated in the
/// plugin's documentation), else by the row before it (the first rows stay until a steady one
/// comes).
void replace_unsteady_spin_rows(std::vector<std::vector<double>>& spin_rows,
                                const SpinWindowDeviations& windows);

}  // namespace stochnav::davar_noise

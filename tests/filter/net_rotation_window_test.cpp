// The tool's net rotation over a sliding window: a full turn, net, within the window is a
// rotation, whatever the rate; less is not, nor is turning back and forth; what left the window
// no longer counts.

#include "stochnav/filter/net_rotation_window.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace stochnav {
namespace {

constexpr double kTurn = 2.0 * std::numbers::pi;
constexpr double kDt = 0.01;  // s, a 100-Hz record

// Feeds `seconds` of a steady `rate` (rad/s) from `t` (advanced).
void turn(NetRotationWindow& window, double& t, double rate, double seconds) {
  const int epochs = static_cast<int>(seconds / kDt + 0.5);
  for (int k = 0; k < epochs; ++k) {
    t += kDt;
    window.add(t, rate * kDt);
  }
}

TEST(NetRotationWindow, AFullTurnWithinTheWindowIsARotationAtAnyRate) {
  for (const double rpm : {0.2, 1.0, 60.0, -160.0}) {
    NetRotationWindow window(600);
    double t = 0.0;
    const double rate = rpm * kTurn / 60.0;
    const double one_turn_s = 60.0 / std::abs(rpm);
    turn(window, t, rate, 0.95 * one_turn_s);
    EXPECT_FALSE(window.rotating()) << rpm;
    turn(window, t, rate, 0.1 * one_turn_s);
    EXPECT_TRUE(window.rotating()) << rpm;
    EXPECT_NEAR(window.net_rad(), rate * 1.05 * one_turn_s, 0.02 * kTurn) << rpm;
  }
}

TEST(NetRotationWindow, TurningBackAndForthOrHalfATurnIsNot) {
  NetRotationWindow window(600);
  double t = 0.0;
  for (int k = 0; k < 50; ++k) {  // rocking: a quarter turn each way, 500 s
    turn(window, t, kTurn / 20.0, 5.0);
    turn(window, t, -kTurn / 20.0, 5.0);
  }
  EXPECT_FALSE(window.rotating());
  EXPECT_NEAR(window.net_rad(), 0.0, 1e-9);
  turn(window, t, kTurn / 20.0, 10.0);  // an orientation: half a turn
  EXPECT_FALSE(window.rotating());
}

TEST(NetRotationWindow, WhatLeftTheWindowNoLongerCounts) {
  NetRotationWindow window(600);
  double t = 0.0;
  turn(window, t, kTurn, 10.0);  // ten turns, then still
  EXPECT_TRUE(window.rotating());
  turn(window, t, 0.0, 580.0);
  EXPECT_TRUE(window.rotating()) << "still within the window";
  turn(window, t, 0.0, 20.0);
  EXPECT_FALSE(window.rotating());
  EXPECT_NEAR(window.net_rad(), 0.0, 1e-9);
  // A gap in the record longer than the window empties it too.
  turn(window, t, kTurn, 2.0);
  t += 1000.0;
  window.add(t, 0.0);
  EXPECT_FALSE(window.rotating());
  EXPECT_EQ(window.net_rad(), 0.0);
}

}  // namespace
}  // namespace stochnav

// The positioning move: its profile against the kinematics it must obey (continuity, the limits,
// the distance), checked by integrating its velocity numerically.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "server/drive/point_to_point_move.hpp"

namespace netmc::drive {
namespace {

// Integrates velocity_m_s with the trapezoid rule and compares it with position_m everywhere;
// checks the limits and the end state.
void check_move(double from, double v0, double to, double vmax, double amax) {
  const PointToPointMove move(from, v0, to, vmax, amax);
  const double dt = 1e-5;
  double integrated = from, previous_v = move.velocity_m_s(0.0), worst = 0.0;
  for (double t = dt; t <= move.duration_s() + 0.01; t += dt) {
    const double v = move.velocity_m_s(t);
    integrated += (v + previous_v) / 2.0 * dt;
    worst = std::max(worst, std::abs(integrated - move.position_m(t)));
    if (t > std::abs(v0) / amax) {
      EXPECT_LE(std::abs(v), vmax * (1 + 1e-12)) << t;
    }
    EXPECT_LE(std::abs(v - previous_v), amax * dt * (1 + 1e-9)) << t;  // no step in velocity
    previous_v = v;
  }
  EXPECT_LT(worst, 1e-9) << from << " " << v0 << " " << to;
  EXPECT_EQ(move.position_m(move.duration_s() + 1.0), to);
  EXPECT_NEAR(move.velocity_m_s(move.duration_s()), 0.0, 1e-12);
}

TEST(PointToPointMove, ObeysItsLimitsAndArrivesAtRest) {
  check_move(0.0, 0.0, 0.06, 0.05, 0.5);        // a trapezoid: 1.3 s
  check_move(0.06, 0.0, 0.0599, 0.05, 0.5);     // a triangle
  check_move(0.05, 0.008, 0.06, 0.05, 0.5);     // moving: stops, then goes
  check_move(0.05, -0.03, 0.04, 0.05, 0.5);     // moving the way it goes
  check_move(0.05, 0.02, 0.05, 0.05, 0.5);      // moving, back to where it was
  check_move(0.02, 0.0, 0.02, 0.05, 0.5);       // already there
}

TEST(PointToPointMove, TakesTheTimeOptimalTrapezoidFromRest) {
  // 60 mm at 50 mm/s and 0.5 m/s^2: 0.1 s to reach the speed (2.5 mm), 1.1 s cruise, 0.1 s down.
  const PointToPointMove move(0.0, 0.0, 0.06, 0.05, 0.5);
  EXPECT_NEAR(move.duration_s(), 1.3, 1e-12);
  EXPECT_NEAR(move.position_m(0.65), 0.03, 1e-12);
  EXPECT_THROW(PointToPointMove(0.0, 0.0, std::nan(""), 0.05, 0.5), std::invalid_argument);
  EXPECT_THROW(PointToPointMove(0.0, 0.0, 0.1, 0.0, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::drive

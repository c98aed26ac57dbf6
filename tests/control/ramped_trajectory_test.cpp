// The motions of paper 004's Table 4 (as netmc assumes them [A]) against closed forms: the circle with
// quintic angle ramps that starts and ends at rest, the jerk-limited rest-to-rest move, and the
// sharp-angle polyline built from it (continuity, the limits, the exact end point).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/jerk_limited_move.hpp"
#include "control/trajectory/polyline_trajectory.hpp"

namespace netmc::control {
namespace {

constexpr double kPi = std::numbers::pi;

CircleParameters paper004_circle() {
  CircleParameters p;
  p.radius_m = 1.0 / (5.0 * kPi);
  p.period_s = 2.0;
  p.ramp_s = 0.2;
  return p;
}

TEST(RampedCircle, AngleFollowsTheQuinticRampAndTheCruiseRate) {
  const CircleTrajectory circle(paper004_circle());
  // Each ramp covers half the cruise rate's angle: 2 pi = w (2 s - 0.2 s).
  const double w = 2 * kPi / 1.8, ramp = 0.2;
  EXPECT_DOUBLE_EQ(circle.duration_s(), 2.0);
  for (const double t : {0.0, 0.05, 0.1, 0.2}) {
    const double s = t / ramp;
    const auto a = circle.angle_at(t);
    EXPECT_NEAR(a.angle, w * ramp * (std::pow(s, 3) - 0.5 * std::pow(s, 4)), 1e-14) << t;
    EXPECT_NEAR(a.rate, w * (3 * s * s - 2 * s * s * s), 1e-13) << t;
    EXPECT_NEAR(a.acceleration, w / ramp * (6 * s - 6 * s * s), 1e-12) << t;
  }
  EXPECT_NEAR(circle.angle_at(1.0).angle, w * (1.0 - 0.1), 1e-14);
  EXPECT_NEAR(circle.angle_at(1.0).rate, w, 1e-15);
  EXPECT_NEAR(circle.angle_at(2.0).angle, 2 * kPi, 1e-14);
  // At rest at both ends, and holding the end point after the duration.
  for (const double t : {-1.0, 0.0, 2.0, 2.5}) {
    const auto p = circle.sample(t);
    EXPECT_EQ(p.velocity.norm(), 0.0) << t;
    EXPECT_EQ(p.acceleration.norm(), 0.0) << t;
  }
  EXPECT_EQ(circle.sample(2.0).position, circle.sample(2.5).position);
  EXPECT_NEAR((circle.sample(2.5).position - circle.sample(0.0).position).norm(), 0.0, 1e-16);
  // Peak speed w R (0.2 m/s x 10/9) and peak acceleration R w^2 on the cruise.
  EXPECT_NEAR(circle.sample(1.0).velocity.norm(), w / (5 * kPi), 1e-15);
  EXPECT_NEAR(circle.sample(1.0).acceleration.norm(), w * w / (5 * kPi), 1e-14);
}

TEST(RampedCircle, PositionVelocityAndAccelerationAreContinuousAndConsistent) {
  const CircleTrajectory circle(paper004_circle());
  const double dt = 1e-7;
  // Across the ramp junctions both sides agree to first order in dt.
  for (const double t : {0.2, 1.8}) {
    const auto before = circle.sample(t - dt), after = circle.sample(t + dt);
    EXPECT_LT((after.position - before.position).norm(), 1e-7) << t;
    EXPECT_LT((after.velocity - before.velocity).norm(), 1e-6) << t;
    EXPECT_LT((after.acceleration - before.acceleration).norm(), 1e-4) << t;
  }
  // Velocity and acceleration are the derivatives of position and velocity everywhere.
  const double h = 1e-6;
  for (const double t : {0.03, 0.15, 0.7, 1.85, 1.99}) {
    const auto p = circle.sample(t);
    const Eigen::Vector2d v = (circle.sample(t + h).position - circle.sample(t - h).position) / (2 * h);
    const Eigen::Vector2d a = (circle.sample(t + h).velocity - circle.sample(t - h).velocity) / (2 * h);
    EXPECT_LT((v - p.velocity).norm(), 1e-8) << t;
    EXPECT_LT((a - p.acceleration).norm(), 1e-6) << t;
  }
  // The contour is the circle whatever the timing.
  for (const double t : {0.1, 1.0, 1.9}) EXPECT_NEAR(circle.contour_error(circle.sample(t).position), 0.0, 1e-16);
}

TEST(RampedCircle, RefusesARampLongerThanHalfTheRun) {
  CircleParameters p = paper004_circle();
  p.ramp_s = 1.01;
  try {
    CircleTrajectory circle(p);
    ADD_FAILURE();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("circle ramp"), std::string::npos);
  }
  p.ramp_s = -0.1;
  EXPECT_THROW(CircleTrajectory circle(p), std::invalid_argument);
  p.ramp_s = 1.0;  // ramps meet in the middle: no cruise
  EXPECT_NEAR(CircleTrajectory(p).angle_at(2.0).angle, 2 * kPi, 1e-14);
}

// The largest |jerk| by differencing the acceleration, and the largest jumps between samples.
struct Smoothness {
  double jerk = 0.0, position_step = 0.0, speed_step = 0.0, acceleration_step = 0.0;
};
Smoothness smoothness_of(const JerkLimitedMove& move, double dt) {
  Smoothness out;
  MoveState previous = move.at(0.0);
  for (double t = dt; t <= move.duration_s() + 2 * dt; t += dt) {
    const MoveState now = move.at(t);
    out.jerk = std::max(out.jerk, std::abs(now.acceleration - previous.acceleration) / dt);
    out.position_step = std::max(out.position_step, std::abs(now.position - previous.position));
    out.speed_step = std::max(out.speed_step, std::abs(now.speed - previous.speed));
    out.acceleration_step = std::max(out.acceleration_step, std::abs(now.acceleration - previous.acceleration));
    previous = now;
  }
  return out;
}

TEST(JerkLimitedMove, SevenPhaseProfileWhenEveryLimitIsReached) {
  // L = 0.1 m, V = 0.1 m/s, A = 1 m/s^2, J = 100 m/s^3: jerk phases A/J = 0.01 s, constant
  // acceleration V/A - A/J = 0.09 s, accelerating 0.11 s over V x 0.11/2, cruise (L - V x 0.11)/V.
  const JerkLimitedMove move(0.1, 0.1, 1.0, 100.0);
  EXPECT_NEAR(move.jerk_time_s(), 0.01, 1e-15);
  EXPECT_NEAR(move.constant_acceleration_time_s(), 0.09, 1e-15);
  EXPECT_NEAR(move.cruise_time_s(), 0.89, 1e-14);
  EXPECT_NEAR(move.duration_s(), 1.11, 1e-14);
  EXPECT_EQ(move.peak_speed_m_s(), 0.1);
  EXPECT_NEAR(move.peak_acceleration_m_s2(), 1.0, 1e-15);
  // Closed forms inside the phases.
  EXPECT_NEAR(move.at(0.005).position, 100.0 * std::pow(0.005, 3) / 6, 1e-18);
  EXPECT_NEAR(move.at(0.005).acceleration, 0.5, 1e-15);
  EXPECT_NEAR(move.at(0.05).speed, 0.5 * 100 * 0.01 * 0.01 + 1.0 * 0.04, 1e-15);
  EXPECT_NEAR(move.at(0.5).position, 0.1 * 0.11 / 2 + 0.1 * (0.5 - 0.11), 1e-15);
  EXPECT_EQ(move.at(0.5).acceleration, 0.0);
  // Exact end point, at rest; and at rest before the start.
  const MoveState end = move.at(move.duration_s());
  EXPECT_EQ(end.position, 0.1);
  EXPECT_EQ(end.speed, 0.0);
  EXPECT_EQ(end.acceleration, 0.0);
  EXPECT_EQ(move.at(5.0).position, 0.1);
  EXPECT_EQ(move.at(-1.0).position, 0.0);
  const Smoothness s = smoothness_of(move, 1e-5);
  EXPECT_LE(s.jerk, 100.0 * (1 + 1e-9));
  EXPECT_LT(s.position_step, 0.1 * 1e-5 * (1 + 1e-6));  // no jump beyond V dt
  EXPECT_LT(s.speed_step, 1.0 * 1e-5 * (1 + 1e-6));     // nor beyond A dt
  EXPECT_LT(s.acceleration_step, 100.0 * 1e-5 * (1 + 1e-6));
}

TEST(JerkLimitedMove, ShortMovesPeakBelowTheLimits) {
  // Too short for the acceleration limit: L = 2 v^1.5 / sqrt(J) with no constant phase.
  const JerkLimitedMove tiny(0.001, 0.1, 1.0, 10.0);
  const double v = std::pow(0.5 * 0.001 * std::sqrt(10.0), 2.0 / 3.0);
  EXPECT_NEAR(tiny.peak_speed_m_s(), v, 1e-15);
  EXPECT_NEAR(tiny.constant_acceleration_time_s(), 0.0, 1e-15);
  EXPECT_NEAR(tiny.cruise_time_s(), 0.0, 1e-13);
  EXPECT_NEAR(tiny.peak_acceleration_m_s2(), std::sqrt(v * 10.0), 1e-14);
  EXPECT_LT(tiny.peak_acceleration_m_s2(), 1.0);
  EXPECT_EQ(tiny.at(tiny.duration_s()).position, 0.001);
  EXPECT_NEAR(tiny.at(0.5 * tiny.duration_s()).speed, v, 1e-15);
  // Reaches the acceleration limit but not the speed: L = v (A/J + v/A).
  const JerkLimitedMove shorter(0.005, 0.1, 1.0, 100.0);
  const double w = 0.5 * (-0.01 + std::sqrt(1e-4 + 0.02));
  EXPECT_NEAR(shorter.peak_speed_m_s(), w, 1e-15);
  EXPECT_NEAR(shorter.peak_acceleration_m_s2(), 1.0, 1e-15);
  EXPECT_NEAR(shorter.constant_acceleration_time_s(), w - 0.01, 1e-15);
  EXPECT_EQ(shorter.at(shorter.duration_s()).position, 0.005);
  for (const auto* move : {&tiny, &shorter}) {
    const Smoothness s = smoothness_of(*move, 1e-6);
    EXPECT_LE(s.jerk, (move == &tiny ? 10.0 : 100.0) * (1 + 1e-6));
    EXPECT_LT(s.speed_step, 1e-6 * (1 + 1e-6));
  }
  EXPECT_THROW(JerkLimitedMove(0.1, 0.1, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(JerkLimitedMove(0.0, 0.1, 1.0, 1.0), std::invalid_argument);
}

PolylineParameters sharp_angle() {
  PolylineParameters p;
  p.points = {{0.0, 0.0}, {0.1, 0.0}, {0.1, 0.1}};
  p.max_speed_m_s = 0.1;
  p.max_acceleration_m_s2 = 1.0;
  p.max_jerk_m_s3 = 10.0;
  return p;
}

TEST(JerkLimitedPolyline, StopsAtTheCornerAndEndsExactly) {
  const PolylineTrajectory path(sharp_angle());
  // Per segment: jerk phases sqrt(V/J) = 0.1 s reaching exactly A = 1 m/s^2, cruise 0.8 s.
  EXPECT_NEAR(path.duration_s(), 2.4, 1e-14);
  ASSERT_EQ(path.corner_times_s().size(), 1u);
  const double corner = path.corner_times_s().front();
  EXPECT_NEAR(corner, 1.2, 1e-14);
  const auto at_corner = path.sample(corner);
  EXPECT_EQ(at_corner.position, Eigen::Vector2d(0.1, 0.0));
  EXPECT_EQ(at_corner.velocity.norm(), 0.0);
  EXPECT_EQ(at_corner.acceleration.norm(), 0.0);
  const auto end = path.sample(path.duration_s());
  EXPECT_EQ(end.position, Eigen::Vector2d(0.1, 0.1));
  EXPECT_EQ(path.sample(3.0).position, Eigen::Vector2d(0.1, 0.1));
  EXPECT_EQ(end.velocity.norm(), 0.0);
  // Acceleration continuous through the corner, jerk within the bound along the whole path.
  const double dt = 1e-5;
  double jerk = 0.0, acceleration_step = 0.0;
  for (double t = dt; t <= path.duration_s(); t += dt) {
    const Eigen::Vector2d step = path.sample(t).acceleration - path.sample(t - dt).acceleration;
    jerk = std::max(jerk, step.norm() / dt);
    acceleration_step = std::max(acceleration_step, step.norm());
    EXPECT_LE(path.sample(t).velocity.norm(), 0.1 * (1 + 1e-12));
  }
  EXPECT_LE(jerk, 10.0 * (1 + 1e-9));
  EXPECT_NE(path.describe().find("jmax=10 m/s^3"), std::string::npos);
}

TEST(JerkLimitedPolyline, RefusesACornerSpeed) {
  PolylineParameters p = sharp_angle();
  p.corner_speed_m_s = 0.05;
  try {
    PolylineTrajectory path(p);
    ADD_FAILURE();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("polyline corner speed"), std::string::npos);
  }
  p.corner_speed_m_s = 0.0;
  p.max_jerk_m_s3 = -1.0;
  EXPECT_THROW(PolylineTrajectory path(p), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control

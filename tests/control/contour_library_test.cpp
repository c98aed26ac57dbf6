// The contour library beyond circle/ellipse/line: Lissajous figures, sharp-corner polylines with
// trapezoidal speed, C2 cubic splines and the feed-rate profile, checked against finite
// differences, a second arc-length method, brute-force distances and the profile's limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>

#include "control/trajectory/cubic_spline_curve.hpp"
#include "control/trajectory/ellipse_trajectory.hpp"
#include "control/trajectory/feed_rate_trajectory.hpp"
#include "control/trajectory/lissajous_trajectory.hpp"
#include "control/trajectory/polyline_trajectory.hpp"
#include "control/task_space/task_frame.hpp"

namespace netmc::control {
namespace {

// Central differences of position and velocity at random times. The velocity must match
// everywhere; the acceleration wherever it does not jump within the stencil (phase changes of a
// piecewise-constant tangential acceleration), and most samples must be such places.
void expect_consistent_derivatives(const ReferenceTrajectory& trajectory, double velocity_scale,
                                   double acceleration_scale) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> when(0.0, trajectory.duration_s());
  const double dt = 1e-6 * trajectory.duration_s();
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const double t = std::clamp(when(random), 2 * dt, trajectory.duration_s() - 2 * dt);
    const auto p = trajectory.sample(t);
    const auto before = trajectory.sample(t - dt), after = trajectory.sample(t + dt);
    const Eigen::Vector2d v = (after.position - before.position) / (2 * dt);
    EXPECT_LT((v - p.velocity).norm(), 1e-6 * velocity_scale) << t;
    if ((after.acceleration - before.acceleration).norm() > 1e-3 * acceleration_scale) continue;
    const Eigen::Vector2d a = (after.velocity - before.velocity) / (2 * dt);
    EXPECT_LT((a - p.acceleration).norm(), 1e-5 * acceleration_scale) << t;
    ++checked;
  }
  EXPECT_GT(checked, 300);
}

double polyline_length(const std::function<Eigen::Vector2d(double)>& position, double span, int n) {
  double length = 0.0;
  Eigen::Vector2d previous = position(0.0);
  for (int i = 1; i <= n; ++i) {
    const Eigen::Vector2d current = position(span * i / n);
    length += (current - previous).norm();
    previous = current;
  }
  return length;
}

LissajousParameters figure_3_2() {
  LissajousParameters p;
  p.center = {0.05, 0.04};
  p.amplitude_x_m = 0.02;
  p.amplitude_y_m = 0.015;
  p.frequency_x = 3;
  p.frequency_y = 2;
  p.phase_rad = 0.3;
  p.period_s = 12.0;
  return p;
}

std::vector<Eigen::Vector2d> closed_spline_points() {
  // A rounded, non-convex loop run counter-clockwise, back to its start.
  return {{0.0, 0.0}, {0.03, -0.005}, {0.05, 0.01}, {0.04, 0.03}, {0.02, 0.02}, {0.005, 0.035}, {-0.01, 0.015}, {0.0, 0.0}};
}

TEST(LissajousTrajectory, DerivativesArcLengthAndContourError) {
  const LissajousTrajectory figure(figure_3_2());
  expect_consistent_derivatives(figure, 0.03, 0.05);
  // Closed after one period; x = cx + ax sin(p w t + phase).
  EXPECT_LT((figure.sample(0.0).position - figure.sample(12.0).position).norm(), 1e-15);
  EXPECT_NEAR(figure.sample(1.0).position.x(), 0.05 + 0.02 * std::sin(3 * 2 * std::numbers::pi / 12.0 + 0.3), 1e-15);
  // Arc length (numerical frame's perimeter, trapezoid on |v|) against a fine chord sum.
  const auto frame = make_task_frame(figure);
  const double chords = polyline_length([&](double t) { return figure.sample(t).position; }, 12.0, 400000);
  EXPECT_NEAR(frame->perimeter_m(), chords, 1e-7 * chords);
  // Off the curve along the right normal: the distance, signed by the side.
  for (double t : {0.7, 3.1, 8.8}) {
    const auto c = figure.sample(t);
    const Eigen::Vector2d right = Eigen::Vector2d(c.velocity.y(), -c.velocity.x()).normalized();
    EXPECT_NEAR(figure.contour_error(c.position), 0.0, 1e-12);
    EXPECT_NEAR(figure.contour_error(c.position + 1e-4 * right), 1e-4, 1e-10) << t;
    EXPECT_NEAR(figure.contour_error(c.position - 1e-4 * right), -1e-4, 1e-10) << t;
  }
}

TEST(LissajousTrajectory, RejectsRetracingFiguresAndBadFrequencies) {
  LissajousParameters line = figure_3_2();
  line.frequency_x = line.frequency_y = 1;
  line.phase_rad = 0.0;
  EXPECT_THROW(LissajousTrajectory{line}, std::invalid_argument);
  LissajousParameters zero = figure_3_2();
  zero.frequency_y = 0;
  EXPECT_THROW(LissajousTrajectory{zero}, std::invalid_argument);
}

PolylineParameters square(double corner_speed = 0.0) {
  PolylineParameters p;
  p.points = {{0.0, 0.0}, {0.02, 0.0}, {0.02, 0.01}, {0.0, 0.01}, {0.0, 0.0}};
  p.max_speed_m_s = 0.01;
  p.max_acceleration_m_s2 = 0.05;
  p.corner_speed_m_s = corner_speed;
  return p;
}

TEST(PolylineTrajectory, TrapezoidalSpeedStopsAtEveryCorner) {
  const PolylineTrajectory path(square());
  EXPECT_TRUE(path.closed());
  EXPECT_DOUBLE_EQ(path.length_m(), 0.06);
  // Per segment (from rest to rest, top speed reached): L / vmax + vmax / a.
  EXPECT_NEAR(path.duration_s(), 2 * (0.02 / 0.01 + 0.2) + 2 * (0.01 / 0.01 + 0.2), 1e-12);
  expect_consistent_derivatives(path, 0.01, 0.05);
  EXPECT_LT(path.sample(2.2).velocity.norm(), 1e-15);  // the first corner
  EXPECT_LT((path.sample(2.2).position - Eigen::Vector2d(0.02, 0.0)).norm(), 1e-15);
  EXPECT_LT(path.sample(path.duration_s()).velocity.norm(), 1e-15);
  EXPECT_LT(path.sample(path.duration_s()).position.norm(), 1e-15);
  for (int i = 0; i <= 1000; ++i) {
    const auto p = path.sample(path.duration_s() * i / 1000);
    EXPECT_LE(p.velocity.norm(), 0.01 + 1e-15);
    EXPECT_LE(p.acceleration.norm(), 0.05 + 1e-15);
  }
  // A short segment never reaches the top speed: a triangle, 2 sqrt(L / a).
  PolylineParameters short_hop = square();
  short_hop.points = {{0.0, 0.0}, {0.001, 0.0}};
  EXPECT_NEAR(PolylineTrajectory(short_hop).duration_s(), 2 * std::sqrt(0.001 / 0.05), 1e-12);
}

TEST(PolylineTrajectory, CornerSpeed) {
  const PolylineTrajectory path(square(0.004));
  // From rest to 10 mm/s and down to 4 mm/s on the first segment.
  const double first = 0.2 + (0.01 - 0.004) / 0.05 +
                       (0.02 - (0.01 * 0.01) / (2 * 0.05) - (0.01 * 0.01 - 0.004 * 0.004) / (2 * 0.05)) / 0.01;
  EXPECT_NEAR(path.sample(first).velocity.norm(), 0.004, 1e-12);
  EXPECT_LT((path.sample(first).position - Eigen::Vector2d(0.02, 0.0)).norm(), 1e-12);
  EXPECT_LT(path.duration_s(), PolylineTrajectory(square()).duration_s());
}

// Second method: dense points on every segment.
double brute_force_polyline_distance(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    for (int i = 0; i <= 20000; ++i) {
      best = std::min(best, (points[k] + (points[k + 1] - points[k]) * (i / 20000.0) - q).norm());
    }
  }
  return best;
}

TEST(PolylineTrajectory, ContourErrorIsTheDistanceToTheNearestSegment) {
  PolylineParameters zigzag = square();
  zigzag.points = {{0.0, 0.0}, {0.02, 0.01}, {0.03, -0.01}, {0.05, 0.0}};
  const PolylineTrajectory open(zigzag);
  const PolylineTrajectory closed(square());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> x(-0.01, 0.06), y(-0.02, 0.02);
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector2d q(x(random), y(random));
    EXPECT_NEAR(std::abs(open.contour_error(q)), brute_force_polyline_distance(zigzag.points, q), 2e-7) << q.transpose();
    EXPECT_NEAR(std::abs(closed.contour_error(q)), brute_force_polyline_distance(square().points, q), 2e-7);
  }
  // Signs: closed counter-clockwise square, outside positive (also outside a corner).
  EXPECT_NEAR(closed.contour_error({0.01, 0.004}), -0.004, 1e-15);
  EXPECT_NEAR(closed.contour_error({0.01, -0.003}), 0.003, 1e-15);
  EXPECT_NEAR(closed.contour_error({0.023, 0.014}), 0.005, 1e-15);
  // Clockwise: still positive outside.
  PolylineParameters clockwise = square();
  std::reverse(clockwise.points.begin(), clockwise.points.end());
  EXPECT_NEAR(PolylineTrajectory(clockwise).contour_error({0.01, -0.003}), 0.003, 1e-15);
  // Open: right of travel positive; beyond a convex corner by the bisector of the normals.
  EXPECT_GT(open.contour_error({0.01, 0.0}), 0.0);
  EXPECT_LT(open.contour_error({0.01, 0.01}), 0.0);
  EXPECT_NEAR(open.contour_error({0.02, 0.015}), -0.005, 1e-15);  // left of the first corner, outside it
  EXPECT_NEAR(open.contour_error({0.03, -0.014}), 0.004, 1e-15);
}

TEST(CubicSplineCurve, InterpolatesWithContinuousSecondDerivative) {
  const auto points = closed_spline_points();
  const CubicSplineCurve closed(points);
  EXPECT_TRUE(closed.closed());
  double knot = 0.0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    EXPECT_LT((closed.evaluate(knot).position - points[i]).norm(), 1e-15);
    const double h = 1e-9;
    if (i > 0) {
      const auto left = closed.evaluate(knot - h), right = closed.evaluate(knot + h);
      EXPECT_LT((left.first - right.first).norm(), 1e-6);
      EXPECT_LT((left.second - right.second).norm(), 1e-5 * right.second.norm() + 1e-9);
    }
    knot += (points[i + 1] - points[i]).norm();
  }
  EXPECT_NEAR(closed.span(), knot, 1e-15);
  // Periodic: the seam is as smooth as the knots.
  const auto start = closed.evaluate(0.0), end = closed.evaluate(closed.span());
  EXPECT_LT((start.position - end.position).norm(), 1e-15);
  EXPECT_LT((start.first - end.first).norm(), 1e-12);
  EXPECT_LT((start.second - end.second).norm(), 1e-9 * start.second.norm());
  // First derivatives in u by finite differences inside a piece.
  const double u = 0.3 * closed.span(), du = 1e-7;
  const auto c = closed.evaluate(u);
  EXPECT_LT(((closed.evaluate(u + du).position - closed.evaluate(u - du).position) / (2 * du) - c.first).norm(), 1e-7);
  EXPECT_LT(((closed.evaluate(u + du).first - closed.evaluate(u - du).first) / (2 * du) - c.second).norm(), 1e-5 * c.second.norm());
  // Open, natural ends: no bending at the ends; two points make a straight segment.
  const CubicSplineCurve open({{0.0, 0.0}, {0.01, 0.01}, {0.03, 0.0}});
  EXPECT_LT(open.evaluate(0.0).second.norm(), 1e-12);
  EXPECT_LT(open.evaluate(open.span()).second.norm(), 1e-12);
  EXPECT_LT(CubicSplineCurve({{0.0, 0.0}, {0.01, 0.0}}).evaluate(0.004).position.y(), 1e-18);
  EXPECT_THROW(CubicSplineCurve({{0.0, 0.0}, {0.0, 0.0}, {0.01, 0.0}}), std::invalid_argument);
  EXPECT_THROW(CubicSplineCurve({{0.0, 0.0}}), std::invalid_argument);
}

// v <= feed, |a_t| <= a_t max, v^2 kappa <= a_n max (the discretisation allows a little), and the
// motion starts and ends at rest.
void expect_within_limits(const FeedRateTrajectory& motion, const FeedRateLimits& limits) {
  const auto start = motion.sample(0.0), end = motion.sample(motion.duration_s());
  EXPECT_LT(start.velocity.norm(), 1e-15);
  EXPECT_LT(end.velocity.norm(), 1e-15);
  double fastest = 0.0, largest_normal = 0.0;
  for (int i = 1; i < 20000; ++i) {
    const auto p = motion.sample(motion.duration_s() * i / 20000);
    const double v = p.velocity.norm();
    if (v < 1e-12) continue;
    const double tangential = p.velocity.dot(p.acceleration) / v;
    const double normal = std::abs(p.velocity.x() * p.acceleration.y() - p.velocity.y() * p.acceleration.x()) / v;
    EXPECT_LE(v, limits.feed_m_s * (1 + 1e-12));
    EXPECT_LE(std::abs(tangential), limits.tangential_acceleration_m_s2 * (1 + 1e-6));
    EXPECT_LE(normal, limits.normal_acceleration_m_s2 * 1.01);
    fastest = std::max(fastest, v);
    largest_normal = std::max(largest_normal, normal);
  }
  // The limits are reached, not merely respected.
  EXPECT_GT(fastest, 0.99 * limits.feed_m_s);
  EXPECT_GT(largest_normal, 0.9 * limits.normal_acceleration_m_s2);
  // Distance travelled = arc length.
  double travelled = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) travelled += motion.sample(motion.duration_s() * (i + 0.5) / n).velocity.norm();
  travelled *= motion.duration_s() / n;
  EXPECT_NEAR(travelled, motion.length_m(), 1e-6 * motion.length_m());
}

TEST(FeedRateTrajectory, SplineAtFeedWithinAccelerationLimits) {
  auto curve = std::make_shared<CubicSplineCurve>(closed_spline_points());
  const FeedRateLimits limits{0.02, 0.05, 0.1};
  const FeedRateTrajectory motion(curve, limits);
  // Arc length: Gauss quadrature on the table against a fine chord sum.
  const double chords = polyline_length([&](double u) { return curve->evaluate(u).position; }, curve->span(), 400000);
  EXPECT_NEAR(motion.length_m(), chords, 1e-9 * chords);
  EXPECT_NEAR(motion.arc_length(0.4 * curve->span()),
              polyline_length([&](double u) { return curve->evaluate(u).position; }, 0.4 * curve->span(), 200000), 1e-9);
  expect_consistent_derivatives(motion, 0.02, 0.1);
  expect_within_limits(motion, limits);
  // The points are passed, in order, and the loop closes.
  EXPECT_LT(motion.sample(motion.duration_s()).position.norm(), 1e-15);
  // Outside positive (counter-clockwise loop), against the foot point on a dense polygon.
  for (double t : {0.5, 2.0, 4.5}) {
    const auto c = motion.sample(t);
    const Eigen::Vector2d right = Eigen::Vector2d(c.velocity.y(), -c.velocity.x()).normalized();
    EXPECT_NEAR(motion.contour_error(c.position + 2e-4 * right), 2e-4, 1e-10);
    EXPECT_NEAR(motion.contour_error(c.position - 2e-4 * right), -2e-4, 1e-10);
  }
}

TEST(FeedRateTrajectory, LissajousAtFeedAndOpenSpline) {
  const FeedRateLimits limits{0.015, 0.02, 0.05};
  const FeedRateTrajectory figure(std::make_shared<LissajousCurve>(figure_3_2()), limits);
  expect_consistent_derivatives(figure, 0.015, 0.05);
  expect_within_limits(figure, limits);
  const FeedRateLimits slow{0.02, 0.03, 0.03};
  const FeedRateTrajectory open(
      std::make_shared<CubicSplineCurve>(std::vector<Eigen::Vector2d>{{0.0, 0.0}, {0.02, 0.01}, {0.03, -0.01}, {0.05, 0.0}}),
      slow);
  expect_consistent_derivatives(open, 0.02, 0.03);
  expect_within_limits(open, slow);
  EXPECT_LT((open.sample(open.duration_s()).position - Eigen::Vector2d(0.05, 0.0)).norm(), 1e-15);
}

TEST(FeedRateTrajectory, EllipseAtFeedKeepsItsClosedFormContourError) {
  EllipseParameters e;
  e.center = {0.05, 0.05};
  e.semi_axis_x_m = 0.02;
  e.semi_axis_y_m = 0.005;
  e.start_angle_rad = 0.4;
  e.clockwise = true;
  const FeedRateLimits limits{0.02, 0.03, 0.1};
  const FeedRateTrajectory motion(std::make_shared<EllipseCurve>(e), limits);
  expect_consistent_derivatives(motion, 0.02, 0.1);
  expect_within_limits(motion, limits);
  // Clockwise from the start angle, and positive outside as the closed form says.
  const EllipseTrajectory uniform(e);
  EXPECT_LT((motion.sample(0.0).position - uniform.sample(0.0).position).norm(), 1e-15);
  EXPECT_LT((motion.sample(0.01).velocity.normalized() - uniform.sample(0.0).velocity.normalized()).norm(), 1e-2);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> x(0.02, 0.08), y(0.035, 0.065);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector2d q(x(random), y(random));
    EXPECT_NEAR(motion.contour_error(q), uniform.contour_error(q), 1e-12) << q.transpose();
  }
}

// GTCF on the new contours: rc is the contour error to first order (the numerical frame's rc is
// the exact distance, so the difference stays at rounding), J orthonormal on the contour, J's
// rows the gradients of rc and rm.
void expect_global_frame_is_exact(const ReferenceTrajectory& contour, const std::vector<double>& times) {
  const auto frame = make_task_frame(contour);
  for (double t : times) {
    const auto c = contour.sample(t);
    const Eigen::Vector2d tangent = c.velocity.normalized();
    const Eigen::Vector2d right(tangent.y(), -tangent.x());
    const auto on = frame->at(c.position);
    EXPECT_NEAR(on.rc, 0.0, 1e-12) << t;
    EXPECT_LT((on.jacobian * on.jacobian.transpose() - Eigen::Matrix2d::Identity()).norm(), 1e-6) << t;
    EXPECT_LT((on.jacobian.row(1).transpose() - tangent).norm(), 1e-6) << t;
    double previous = -1.0;
    for (double delta : {2e-4, 1e-4, 5e-5, 2.5e-5}) {
      const Eigen::Vector2d q = c.position + delta * right + 0.5 * delta * tangent;
      const double exact = contour.contour_error(q);
      const double difference = std::abs(frame->at(q).rc - exact);
      EXPECT_NEAR(exact, delta, 0.2 * delta) << t;
      EXPECT_LT(difference, 0.05 * delta) << t;
      if (previous > 1e-12) {
        EXPECT_LT(difference, previous / 3.5) << t << " " << delta;
      }
      previous = difference;
      // grad rc by central differences.
      const double h = 1e-7;
      const Eigen::Vector2d gradient((frame->at(q + Eigen::Vector2d(h, 0)).rc - frame->at(q - Eigen::Vector2d(h, 0)).rc) / (2 * h),
                                    (frame->at(q + Eigen::Vector2d(0, h)).rc - frame->at(q - Eigen::Vector2d(0, h)).rc) / (2 * h));
      EXPECT_LT((gradient - frame->at(q).jacobian.row(0).transpose()).norm(), 1e-4) << t;
    }
    // rm is arc length: a step along the tangent advances it by the step.
    const double h = 1e-6;
    EXPECT_NEAR((frame->at(c.position + h * tangent).rm - frame->at(c.position - h * tangent).rm) / (2 * h), 1.0, 1e-3) << t;
  }
}

TEST(GlobalTaskFrame, ExactOnTheNewContours) {
  const FeedRateTrajectory spline(std::make_shared<CubicSplineCurve>(closed_spline_points()), {0.02, 0.05, 0.1});
  expect_global_frame_is_exact(spline, {0.3, 1.5, 3.0, 5.5});
  // Away from the self-intersections of the figure (each of these points is 5 mm or more from
  // any other part of it).
  const LissajousTrajectory figure(figure_3_2());
  expect_global_frame_is_exact(figure, {0.1, 1.0, 3.1, 4.8, 9.0});
  EllipseParameters e;
  e.center = {0.05, 0.05};
  e.semi_axis_x_m = 0.02;
  e.semi_axis_y_m = 0.008;
  expect_global_frame_is_exact(EllipseTrajectory(e), {0.2, 1.9, 4.0, 6.7});
  // The polyline inside its segments.
  const PolylineTrajectory path(square());
  expect_global_frame_is_exact(path, {1.0, 3.5, 5.0, 6.5});
}

TEST(GlobalTaskFrame, FollowsTheBranchThroughACrossing) {
  // The 3:2 figure crosses itself at t = 0.5 s (and again later in the period). Followed from
  // cycle to cycle, rm advances by the distance travelled; the global search jumps branches.
  const LissajousTrajectory figure(figure_3_2());
  const auto frame = make_task_frame(figure);
  const double dt = 1e-3;
  double rm = frame->at(figure.sample(0.3).position).rm;
  bool global_jumped = false;
  for (double t = 0.3 + dt; t < 0.7; t += dt) {
    const auto c = figure.sample(t);
    // 30 um to the right of travel: near the crossing the other branch is nearer than that.
    const Eigen::Vector2d right = Eigen::Vector2d(c.velocity.y(), -c.velocity.x()).normalized();
    const Eigen::Vector2d q = c.position + 3e-5 * right;
    const auto followed = frame->near(q, rm + c.velocity.norm() * dt);
    EXPECT_NEAR(followed.rm - rm, c.velocity.norm() * dt, 1e-6) << t;
    EXPECT_NEAR(followed.rc, 3e-5, 1e-9) << t;
    global_jumped = global_jumped || std::abs(frame->at(q).rm - followed.rm) > 1e-3;
    rm = followed.rm;
  }
  EXPECT_TRUE(global_jumped);
}

TEST(GlobalTaskFrame, SharpCornerUsesTheChord) {
  const PolylineTrajectory path(square());
  const auto frame = make_task_frame(path);
  // Outside the corner (0.02, 0): rc is the distance to it, J orthonormal, the normal on the bisector.
  const auto r = frame->at({0.023, -0.003});
  EXPECT_NEAR(r.rc, std::hypot(0.003, 0.003), 1e-12);
  EXPECT_LT((r.jacobian * r.jacobian.transpose() - Eigen::Matrix2d::Identity()).norm(), 1e-9);
  EXPECT_LT((r.jacobian.row(0).transpose() - Eigen::Vector2d(1.0, -1.0).normalized()).norm(), 1e-3);
  EXPECT_NEAR(r.rm, 0.02, 1e-8);  // the arc table's trapezoid rule
}

}  // namespace
}  // namespace netmc::control

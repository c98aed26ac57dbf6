// Reference trajectories and their exact contour error against independent computations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/ellipse_trajectory.hpp"
#include "control/trajectory/line_trajectory.hpp"
#include "control/trajectory/point_ellipse_distance.hpp"

namespace netmc::control {
namespace {

TEST(CircleTrajectory, ReproducesPaper001Reference) {
  // x_d = 10 cos(0.25 pi t) + 50, y_d = 10 sin(0.25 pi t) + 50 (mm)
  CircleTrajectory circle({{0.05, 0.05}, 0.01, 8.0});
  for (double t : {0.0, 1.3, 4.0, 7.9}) {
    const auto p = circle.sample(t);
    EXPECT_NEAR(p.position.x(), 0.01 * std::cos(0.25 * std::numbers::pi * t) + 0.05, 1e-15);
    EXPECT_NEAR(p.position.y(), 0.01 * std::sin(0.25 * std::numbers::pi * t) + 0.05, 1e-15);
    EXPECT_NEAR(p.velocity.norm(), 0.01 * 0.25 * std::numbers::pi, 1e-15);  // 7.854 mm/s
  }
  EXPECT_DOUBLE_EQ(circle.duration_s(), 8.0);
}

TEST(CircleTrajectory, DerivativesMatchFiniteDifferences) {
  CircleTrajectory circle({{0.01, -0.02}, 0.03, 2.0, 0.4, true});
  const double t = 0.7, dt = 1e-6;
  const auto p = circle.sample(t);
  const Eigen::Vector2d v = (circle.sample(t + dt).position - circle.sample(t - dt).position) / (2 * dt);
  const Eigen::Vector2d a = (circle.sample(t + dt).velocity - circle.sample(t - dt).velocity) / (2 * dt);
  EXPECT_LT((v - p.velocity).norm(), 1e-8);
  EXPECT_LT((a - p.acceleration).norm(), 1e-7);
}

TEST(CircleTrajectory, ContourErrorIsRadialDistance) {
  CircleTrajectory circle({{0.05, 0.05}, 0.01, 8.0});
  EXPECT_NEAR(circle.contour_error({0.0612, 0.05}), 0.0012, 1e-15);
  EXPECT_NEAR(circle.contour_error({0.05, 0.0415}), -0.0015, 1e-15);
}

TEST(EllipseTrajectory, DerivativesMatchFiniteDifferences) {
  EllipseTrajectory ellipse({{0.05, 0.05}, 0.02, 0.005, 8.0, 0.3});
  const double t = 2.1, dt = 1e-6;
  const auto p = ellipse.sample(t);
  const Eigen::Vector2d v = (ellipse.sample(t + dt).position - ellipse.sample(t - dt).position) / (2 * dt);
  const Eigen::Vector2d a = (ellipse.sample(t + dt).velocity - ellipse.sample(t - dt).velocity) / (2 * dt);
  EXPECT_LT((v - p.velocity).norm(), 1e-10);
  EXPECT_LT((a - p.acceleration).norm(), 1e-8);
}

// Second method: dense sampling of the parameter, then golden-section refinement.
double brute_force_ellipse_distance(double a, double b, const Eigen::Vector2d& q) {
  const auto distance = [&](double phi) {
    return std::hypot(a * std::cos(phi) - q.x(), b * std::sin(phi) - q.y());
  };
  const int n = 20000;
  double best_phi = 0.0, best = distance(0.0);
  for (int i = 1; i < n; ++i) {
    const double phi = 2 * std::numbers::pi * i / n;
    if (distance(phi) < best) {
      best = distance(phi);
      best_phi = phi;
    }
  }
  double lo = best_phi - 2 * std::numbers::pi / n, hi = best_phi + 2 * std::numbers::pi / n;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (distance(m1) < distance(m2)) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  return distance(0.5 * (lo + hi));
}

TEST(PointEllipseDistance, AgreesWithDenseSearchEverywhere) {
  const double a = 0.02, b = 0.005;
  for (double x : {-0.03, -0.0199, -0.01, 0.0, 0.001, 0.015, 0.0201, 0.04}) {
    for (double y : {-0.01, -0.004, 0.0, 0.0005, 0.003, 0.0049, 0.02}) {
      const Eigen::Vector2d q(x, y);
      const auto foot = nearest_point_on_ellipse(a, b, q);
      EXPECT_NEAR(std::abs(foot.signed_distance), brute_force_ellipse_distance(a, b, q), 1e-11)
          << "at (" << x << ", " << y << ")";
      EXPECT_NEAR(std::pow(foot.point.x() / a, 2) + std::pow(foot.point.y() / b, 2), 1.0, 1e-12);
      const bool inside = std::pow(x / a, 2) + std::pow(y / b, 2) < 1.0;
      if (std::abs(foot.signed_distance) > 0) {
        EXPECT_EQ(foot.signed_distance < 0, inside);
      }
    }
  }
}

TEST(PointEllipseDistance, TallEllipseAndCircleLimit) {
  // Major axis along y exercises the axis swap; a = b must give | |q| - r |.
  const Eigen::Vector2d q(0.004, 0.013);
  EXPECT_NEAR(std::abs(nearest_point_on_ellipse(0.005, 0.02, q).signed_distance),
              brute_force_ellipse_distance(0.005, 0.02, q), 1e-11);
  EXPECT_NEAR(nearest_point_on_ellipse(0.01, 0.01, q).signed_distance, q.norm() - 0.01, 1e-15);
}

TEST(LineTrajectory, ConstantVelocityAndSignedSegmentDistance) {
  LineTrajectory line({{0.0, 0.0}, {0.04, 0.03}, 5.0});
  EXPECT_NEAR(line.sample(2.5).position.x(), 0.02, 1e-15);
  EXPECT_NEAR(line.sample(1.0).velocity.norm(), 0.01, 1e-15);
  // Right of travel (direction (0.8, 0.6)) is positive: offset along (0.6, -0.8).
  EXPECT_NEAR(line.contour_error(Eigen::Vector2d(0.02, 0.015) + 0.001 * Eigen::Vector2d(0.6, -0.8)),
              0.001, 1e-15);
  EXPECT_NEAR(line.contour_error(Eigen::Vector2d(0.02, 0.015) - 0.002 * Eigen::Vector2d(0.6, -0.8)),
              -0.002, 1e-15);
  // Beyond the end the distance is to the end point.
  EXPECT_NEAR(std::abs(line.contour_error({0.05, 0.03})), 0.01, 1e-15);
  EXPECT_THROW(LineTrajectory({{0.01, 0.01}, {0.01, 0.01}, 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control

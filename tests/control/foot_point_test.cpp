// Foot-point contour-error estimation (paper 002) against closed forms and the global search.
#include <gtest/gtest.h>

#include <cmath>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/ellipse_trajectory.hpp"
#include "control/trajectory/foot_point.hpp"
#include "control/trajectory/heart_trajectory.hpp"

namespace netmc::control {
namespace {

TEST(FootPoint, NewtonAndSteffensenFindTheCircleDistance) {
  CircleTrajectory circle({{0.075, 0.075}, 0.05, 5.0});
  for (double t : {0.3, 1.7, 4.2}) {
    // Lagging 15 ms behind and 40 um outside: the exact distance is closed-form.
    const auto lagged = circle.sample(t - 0.015);
    const Eigen::Vector2d p = lagged.position + 40e-6 * (lagged.position - Eigen::Vector2d(0.075, 0.075)).normalized();
    const double exact = std::abs(circle.contour_error(p));
    const auto newton = newton_foot_point(circle, p, t);
    const auto steffensen = steffensen_foot_point(circle, p, t);
    EXPECT_NEAR(newton.distance_m, exact, 1e-12);
    EXPECT_NEAR(steffensen.distance_m, exact, 1e-12);
    EXPECT_NEAR(exact_foot_point(circle, p).distance_m, exact, 1e-12);
    // Steffensen's acceleration: fewer updates than the fixed-point (Newton) iteration.
    EXPECT_LT(steffensen.iterations, newton.iterations);
  }
}

TEST(FootPoint, ExactSearchAgreesWithTheEllipseClosedForm) {
  EllipseTrajectory ellipse({{0.0, 0.0}, 0.02, 0.005, 8.0});
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.021, 0.0003), Eigen::Vector2d(-0.003, 0.0049),
                                  Eigen::Vector2d(0.01, -0.006)}) {
    EXPECT_NEAR(exact_foot_point(ellipse, p).distance_m, std::abs(ellipse.contour_error(p)), 1e-10);
  }
}

TEST(HeartTrajectory, DerivativesMatchFiniteDifferencesAndCuspsStop) {
  HeartTrajectory heart({});
  const double dt = 1e-6;
  for (double t : {0.7, 2.3, 6.1}) {
    const auto p = heart.sample(t);
    const Eigen::Vector2d v = (heart.sample(t + dt).position - heart.sample(t - dt).position) / (2 * dt);
    const Eigen::Vector2d a = (heart.sample(t + dt).velocity - heart.sample(t - dt).velocity) / (2 * dt);
    EXPECT_LT((v - p.velocity).norm(), 1e-9);
    EXPECT_LT((a - p.acceleration).norm(), 1e-8);
  }
  EXPECT_LT(heart.sample(0.0).velocity.norm(), 1e-15);  // sharp corners at phi = 0 and pi
  EXPECT_LT(heart.sample(5.0).velocity.norm(), 1e-15);
  // Inside is negative, outside positive.
  EXPECT_LT(heart.contour_error({0.075, 0.075}), 0.0);
  EXPECT_GT(heart.contour_error({0.0, 0.0}), 0.0);
}

}  // namespace
}  // namespace netmc::control

// Contour-error estimators of paper 001 (eq. 11, 13) against the exact contour error.
#include <gtest/gtest.h>

#include <cmath>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/contour_error/contour_error_estimator.hpp"
#include "control/trajectory/line_trajectory.hpp"

namespace netmc::control {
namespace {

TEST(ContourErrorEstimators, ExactOnALine) {
  LineTrajectory line({{0.0, 0.0}, {0.03, 0.01}, 4.0});
  auto reference = line.sample(1.0);
  reference.time_s = 1.0;  // where the foot-point estimators start their search
  for (const auto& name : contour_error_estimator_names()) {
    const auto estimator = make_contour_error_estimator(name, std::make_shared<LineTrajectory>(line));
    for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0.001, -0.002), Eigen::Vector2d(-0.0004, 0.0001)}) {
      const Eigen::Vector2d actual = reference.position + offset;
      EXPECT_NEAR(estimator->estimate(reference, actual).contour_error, line.contour_error(actual),
                  1e-15)
          << name;
    }
  }
}

TEST(ContourErrorEstimators, Paper001GainsOnTheCounterClockwiseCircle) {
  // theta = 0.25 pi t + pi/2 for the paper's circle: cx = sin(theta), cy = cos(theta) (eq. 11).
  CircleTrajectory circle({{0.05, 0.05}, 0.01, 8.0});
  const double t = 1.0;
  const auto reference = circle.sample(t);
  const double theta = 0.25 * std::numbers::pi * t + std::numbers::pi / 2;
  const auto estimate = TangentContourErrorEstimator().estimate(reference, reference.position);
  EXPECT_NEAR(estimate.cx, std::sin(theta), 1e-15);
  EXPECT_NEAR(estimate.cy, std::cos(theta), 1e-15);
  // eq. 13: cx = sin(theta) - ex/(2R), cy = cos(theta) + ey/(2R)
  const Eigen::Vector2d actual = reference.position + Eigen::Vector2d(0.0003, -0.0002);
  const Eigen::Vector2d e = reference.position - actual;
  const auto second = CurvatureContourErrorEstimator().estimate(reference, actual);
  EXPECT_NEAR(second.cx, std::sin(theta) - e.x() / 0.02, 1e-12);
  EXPECT_NEAR(second.cy, std::cos(theta) + e.y() / 0.02, 1e-12);
}

TEST(ContourErrorEstimators, CurvatureEstimateIsSecondOrderAccurateAlongTheTangent) {
  // A lag along the path: the exact error is sqrt(R^2 + s^2) - R ~ s^2/2R; the tangent estimate
  // sees 0 and the curvature estimate matches to O(s^4).
  CircleTrajectory circle({{0.0, 0.0}, 0.01, 8.0});
  const auto reference = circle.sample(0.0);  // at (R, 0), moving +y
  const TangentContourErrorEstimator tangent;
  const CurvatureContourErrorEstimator curvature;
  double previous_error = 0.0;
  for (double s : {1e-3, 5e-4, 2.5e-4}) {
    const Eigen::Vector2d actual = reference.position - Eigen::Vector2d(0.0, s);
    const double exact = circle.contour_error(actual);
    EXPECT_NEAR(tangent.estimate(reference, actual).contour_error, 0.0, 1e-18);
    const double error = std::abs(curvature.estimate(reference, actual).contour_error - exact);
    EXPECT_LT(error, 0.01 * exact);
    if (previous_error > 0.0) {
      EXPECT_NEAR(error / previous_error, 1.0 / 16.0, 0.01);  // O(s^4)
    }
    previous_error = error;
  }
}

TEST(ContourErrorEstimators, SignIsPositiveOutsideACounterClockwiseCircle) {
  CircleTrajectory circle({{0.0, 0.0}, 0.01, 8.0});
  auto reference = circle.sample(3.0);
  reference.time_s = 3.0;
  const Eigen::Vector2d outward = reference.position.normalized();
  for (const auto& name : contour_error_estimator_names()) {
    const auto estimator = make_contour_error_estimator(name, std::make_shared<CircleTrajectory>(circle));
    EXPECT_GT(estimator->estimate(reference, reference.position + 1e-4 * outward).contour_error, 0.0);
    EXPECT_LT(estimator->estimate(reference, reference.position - 1e-4 * outward).contour_error, 0.0);
  }
}

TEST(ContourErrorEstimators, UnknownNameNamesTheField) {
  try {
    make_contour_error_estimator("exactish");
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("estimator: unknown name 'exactish'"), std::string::npos);
  }
}

}  // namespace
}  // namespace netmc::control

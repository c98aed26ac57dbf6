// Global task coordinate frame (thesis ch. 2): rc exact to first order, J orthonormal on the
// contour, closed forms against the numerical foot-point construction.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/ellipse_trajectory.hpp"
#include "control/task_space/task_frame.hpp"

namespace netmc::control {
namespace {

// The thesis's 10:1 ellipse (eq. 2-68), centred at the origin.
constexpr double kA = 0.2, kB = 0.02;

Eigen::Vector2d on_ellipse(double nu) { return {kA * std::cos(nu), kB * std::sin(nu)}; }

TEST(CircleTaskFrame, ExactContourErrorArcLengthAndUnitaryJacobianOnTheContour) {
  CircleTaskFrame frame({0.01, 0.02}, 0.04);
  const Eigen::Vector2d q(0.01 + 0.043 * std::cos(1.0), 0.02 + 0.043 * std::sin(1.0));
  const auto r = frame.at(q);
  EXPECT_NEAR(r.rc, 0.003, 1e-15);
  EXPECT_NEAR(r.rm, 0.04 * 1.0, 1e-15);
  const auto on = frame.at({0.01 + 0.04 * std::cos(2.5), 0.02 + 0.04 * std::sin(2.5)});
  EXPECT_LT((on.jacobian * on.jacobian.transpose() - Eigen::Matrix2d::Identity()).norm(), 1e-14);
}

TEST(EllipseTaskFrame, JacobianIsOrthonormalOnTheContourAndRmIsArcLength) {
  EllipseTaskFrame frame({0.0, 0.0}, kA, kB);
  double previous_rm = -1.0;
  for (double nu = 0.05; nu < 2 * std::numbers::pi; nu += 0.5) {
    const auto r = frame.at(on_ellipse(nu));
    EXPECT_NEAR(r.rc, 0.0, 1e-15);
    EXPECT_LT((r.jacobian * r.jacobian.transpose() - Eigen::Matrix2d::Identity()).norm(), 1e-5) << nu;
    EXPECT_GT(r.rm, previous_rm);  // increases counter-clockwise
    previous_rm = r.rm;
  }
  // A quarter of the perimeter (complete elliptic integral, here by a fine midpoint sum).
  double quarter = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double nu = (i + 0.5) * (std::numbers::pi / 2) / n;
    quarter += std::sqrt(kA * kA * std::sin(nu) * std::sin(nu) + kB * kB * std::cos(nu) * std::cos(nu));
  }
  quarter *= (std::numbers::pi / 2) / n;
  EXPECT_NEAR(frame.at(on_ellipse(std::numbers::pi / 2)).rm, quarter, 1e-7);
}

TEST(EllipseTaskFrame, RcIsExactToFirstOrder) {
  // Lemma 2.1: rc = eps + o(eps). Offsets along a slanted direction shrink by half, so the
  // difference to the exact contour error must shrink at least fourfold (second order or better).
  EllipseTaskFrame frame({0.0, 0.0}, kA, kB);
  EllipseTrajectory ellipse({{0.0, 0.0}, kA, kB, 1.0});
  for (double nu : {0.0, 0.4, 1.3, 3.0}) {  // nu = 0: the vertex of highest curvature
    const Eigen::Vector2d direction = Eigen::Vector2d(1.0, 2.0).normalized();
    double previous = 0.0;
    for (double offset : {4e-4, 2e-4, 1e-4, 5e-5}) {
      const Eigen::Vector2d q = on_ellipse(nu) + offset * direction;
      const double difference = std::abs(frame.at(q).rc - ellipse.contour_error(q));
      EXPECT_LT(difference, 0.05 * std::abs(ellipse.contour_error(q)) + 1e-12) << nu;
      if (previous > 1e-13) {
        EXPECT_LT(difference / previous, 0.3) << nu << " " << offset;
      }
      previous = difference;
    }
  }
}

TEST(TaskFrames, ClosedFormsAgreeWithTheNumericalConstruction) {
  NumericalTaskFrame numerical_ellipse(std::make_shared<EllipseTrajectory>(EllipseParameters{{0.0, 0.0}, kA, kB, 1.0}));
  EllipseTaskFrame ellipse({0.0, 0.0}, kA, kB);
  for (double nu : {0.3, 1.9, 4.4}) {
    const auto closed = ellipse.at(on_ellipse(nu));
    const auto numeric = numerical_ellipse.at(on_ellipse(nu));
    EXPECT_NEAR(closed.rm, numeric.rm, 1e-7);
    EXPECT_LT((closed.jacobian - numeric.jacobian).norm(), 1e-5);
    // Off the contour, rc agrees to first order.
    const Eigen::Vector2d q = on_ellipse(nu) + Eigen::Vector2d(1e-4, -2e-4);
    EXPECT_NEAR(ellipse.at(q).rc, numerical_ellipse.at(q).rc, 2e-6);
  }
  NumericalTaskFrame numerical_circle(std::make_shared<CircleTrajectory>(CircleParameters{{0.0, 0.0}, 0.04, 1.0}));
  CircleTaskFrame circle({0.0, 0.0}, 0.04);
  const Eigen::Vector2d q(0.03, 0.031);
  EXPECT_NEAR(circle.at(q).rc, numerical_circle.at(q).rc, 1e-12);
  EXPECT_NEAR(circle.at(q).rm, numerical_circle.at(q).rm, 1e-8);
}

TEST(CircleTaskFrame, ClockwiseFrameGrowsAlongTheMotionLikeTheNumericalConstruction) {
  // Thesis case B (eq. 2-66): clockwise, r = 4 cm about (0, 5 cm), from angle 0.
  CircleParameters p{{0.0, 0.05}, 0.04, 1.0};
  p.clockwise = true;
  const auto trajectory = std::make_shared<CircleTrajectory>(p);
  NumericalTaskFrame numerical(trajectory);
  CircleTaskFrame circle(p.center, p.radius_m, true);
  const Eigen::Vector2d a(0.031, 0.02), b(0.036, 0.072);  // off the contour, a quarter turn apart
  EXPECT_NEAR(circle.at(a).rc, trajectory->contour_error(a), 1e-12);  // positive outside
  // On the contour J = [outward normal; tangent of travel]; the numerical frame's normal is the
  // right of travel, inward on a clockwise contour.
  const Eigen::Vector2d on = trajectory->sample(0.3).position;
  EXPECT_LT((circle.at(on).jacobian.row(0) + numerical.at(on).jacobian.row(0)).norm(), 1e-6);
  EXPECT_LT((circle.at(on).jacobian.row(1) - numerical.at(on).jacobian.row(1)).norm(), 1e-6);
  // rm differences agree (the origins differ: angle 0 against the motion's start).
  EXPECT_NEAR(std::remainder(circle.at(b).rm - circle.at(a).rm, numerical.perimeter_m()),
              std::remainder(numerical.at(b).rm - numerical.at(a).rm, numerical.perimeter_m()), 1e-7);
  // rm grows at the speed of travel, 2 pi R per revolution.
  EXPECT_NEAR(circle.at(trajectory->sample(0.31).position).rm - circle.at(on).rm,
              2.0 * std::numbers::pi * 0.04 * 0.01, 1e-12);
}

}  // namespace
}  // namespace netmc::control

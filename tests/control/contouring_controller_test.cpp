// Composition of per-axis control and contour compensation (paper 001, eq. 15). (Names and
// gains of the compositions: tests/server/controller_registry_test.cpp.)
#include <gtest/gtest.h>

#include "control/axis/pid_axis_controller.hpp"
#include "control/cross_coupling/contouring_controller.hpp"
#include "control/cross_coupling/pid_cross_coupling.hpp"
#include "control/trajectory/circle_trajectory.hpp"

namespace netmc::control {
namespace {

TEST(ContouringController, DistributesTheCouplingCommandWithTheEstimatorGains) {
  // Per-axis PID with zero gains leaves only the coupling term: U = (-cx u_e, cy u_e).
  ContouringController controller(std::make_unique<PidAxisController>(PidAxisGains{}, 0.005),
                                  std::make_unique<PidAxisController>(PidAxisGains{}, 0.005),
                                  make_contour_error_estimator("curvature"),
                                  std::make_unique<PidCrossCoupling>(PidCrossCouplingGains{2.0, 0.0, 0.0}, 0.005));
  CircleTrajectory circle({{0.05, 0.05}, 0.01, 8.0});
  controller.begin_iteration(circle.sample(0).position, 10);
  const auto reference = circle.sample(0.5);
  const Eigen::Vector2d measured = reference.position + Eigen::Vector2d(2e-4, 1e-4);
  const auto cycle = controller.step(0, reference, measured);
  const auto estimate = CurvatureContourErrorEstimator().estimate(reference, measured);
  EXPECT_NEAR(cycle.coupling_command, 2.0 * estimate.contour_error, 1e-15);
  EXPECT_NEAR(cycle.command.x(), -estimate.cx * 2.0 * estimate.contour_error, 1e-15);
  EXPECT_NEAR(cycle.command.y(), estimate.cy * 2.0 * estimate.contour_error, 1e-15);
  // The correction points back towards the contour: outward error, inward command.
  const Eigen::Vector2d outward = (reference.position - Eigen::Vector2d(0.05, 0.05)).normalized();
  EXPECT_GT(estimate.contour_error, 0.0);
  EXPECT_LT(cycle.command.dot(outward), 0.0);
}

}  // namespace
}  // namespace netmc::control

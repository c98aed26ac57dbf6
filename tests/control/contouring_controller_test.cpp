// Composition of per-axis control and contour compensation (paper 001, eq. 15) and the catalog.
#include <gtest/gtest.h>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/controller_catalog.hpp"

namespace netmc::control {
namespace {

TEST(ContouringController, DistributesTheCouplingCommandWithTheEstimatorGains) {
  // Per-axis PID with zero gains leaves only the coupling term: U = (-cx u_e, cy u_e).
  ControllerSettings settings;
  settings.pidccc = {2.0, 0.0, 0.0};
  auto controller = make_contouring_controller("pid+pidccc", settings, 0.005);
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

TEST(ControllerCatalog, BuildsEveryCombinationAndRejectsUnknownNames) {
  for (const auto& axis : axis_controller_names()) {
    EXPECT_NO_THROW(make_contouring_controller(axis, {}, 0.005));
    for (const auto& compensator : contour_compensator_names()) {
      EXPECT_NO_THROW(make_contouring_controller(axis + "+" + compensator, {}, 0.005));
    }
  }
  for (const char* bad : {"adrcx", "adrc+", "adrc+qft", "", "+ilccc"}) {
    try {
      make_contouring_controller(bad, {}, 0.005);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("controller: unknown name"), std::string::npos);
    }
  }
  ControllerSettings nan_gain;
  nan_gain.adrc.kp = std::nan("");
  EXPECT_THROW(make_contouring_controller("adrc", nan_gain, 0.005), std::invalid_argument);
  EXPECT_THROW(make_contouring_controller("adrc", {}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control

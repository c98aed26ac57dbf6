// Task-space SARC: the projection keeps the uncertainty estimate within its bound; the GTCF and
// LTCF errors agree with the frames' definitions.
#include <gtest/gtest.h>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/task_space/task_space_sarc.hpp"

namespace netmc::control {
namespace {

TEST(TaskSpaceSarc, ProjectionKeepsTheEstimateWithinItsBound) {
  CircleTrajectory circle({{0.0, 0.0}, 0.04, 0.4});
  auto frame = make_task_frame(circle);
  SarcGains gains;
  TaskSpaceSarc sarc(gains, 2e-4, frame);
  sarc.begin_iteration(circle.sample(0.0).position, 1000);
  // The axis stays 2 mm outside and behind for a long time: the gradient law keeps pushing.
  for (std::size_t k = 0; k < 5000; ++k) {
    const auto reference = circle.sample(static_cast<double>(k) * 2e-4);
    sarc.step(k, reference, 1.05 * reference.position);
    for (int i = 0; i < 2; ++i) {
      EXPECT_LE(std::abs(sarc.uncertainty_estimate()[i]), gains.uncertainty_bound[i] + 1e-12);
    }
  }
  // It did push: at least one component reached the bound.
  EXPECT_NEAR(sarc.uncertainty_estimate().cwiseAbs().maxCoeff(), 1.5, 1e-9);
}

TEST(TaskSpaceSarc, ReportsTheContourCoordinateAsItsEstimate) {
  CircleTrajectory circle({{0.0, 0.0}, 0.04, 0.4});
  TaskSpaceSarc global(SarcGains{}, 2e-4, make_task_frame(circle));
  TaskSpaceSarc local(SarcGains{}, 2e-4, nullptr);
  const auto reference = circle.sample(0.1);
  global.begin_iteration(reference.position, 10);
  local.begin_iteration(reference.position, 10);
  const Eigen::Vector2d outside = reference.position * (0.0403 / 0.04);  // 0.3 mm outside
  EXPECT_NEAR(global.step(0, reference, outside).estimate.contour_error, 0.0003, 1e-12);
  // LTCF's first row is the left normal of travel: inward for a counter-clockwise circle.
  EXPECT_NEAR(local.step(0, reference, outside).estimate.contour_error, -0.0003, 1e-12);
  EXPECT_THROW(TaskSpaceSarc(SarcGains{}, 0.0, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control

// HaltedTrajectory re-times a motion: before the halt it is the motion, during it the motion's
// position at rest, after it the motion shifted by the halt's length; the contour is unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/trajectory/halted_trajectory.hpp"
#include "control/task_space/task_frame.hpp"

namespace netmc::control {
namespace {

std::shared_ptr<const CircleTrajectory> circle() {
  CircleParameters p;
  p.center = {0.05, 0.05};
  p.radius_m = 0.01;
  p.period_s = 8.0;
  return std::make_shared<CircleTrajectory>(p);
}

TEST(HaltedTrajectory, FreezesTheReferenceTimeAndThenShiftsIt) {
  const auto motion = circle();
  const HaltedTrajectory halted(motion, 2.0, 0.5);
  EXPECT_DOUBLE_EQ(halted.duration_s(), 8.5);
  EXPECT_DOUBLE_EQ(halted.period_s(), 8.0);
  const ReferencePoint before = halted.sample(1.0);
  EXPECT_TRUE(before.position.isApprox(motion->sample(1.0).position));
  EXPECT_TRUE(before.velocity.isApprox(motion->sample(1.0).velocity));
  for (double t : {2.0, 2.2, 2.499}) {
    const ReferencePoint during = halted.sample(t);
    EXPECT_TRUE(during.position.isApprox(motion->sample(2.0).position)) << t;
    EXPECT_EQ(during.velocity.norm(), 0.0) << t;
    EXPECT_EQ(during.acceleration.norm(), 0.0) << t;
  }
  // Closed form of the circle after the halt: angle = 2 pi (t - 0.5) / 8 from the +x axis.
  const double t = 5.0;
  const double angle = 2.0 * std::numbers::pi * (t - 0.5) / 8.0;
  const ReferencePoint after = halted.sample(t);
  EXPECT_NEAR(after.position.x(), 0.05 + 0.01 * std::cos(angle), 1e-15);
  EXPECT_NEAR(after.position.y(), 0.05 + 0.01 * std::sin(angle), 1e-15);
  EXPECT_NEAR(after.velocity.norm(), 2.0 * std::numbers::pi * 0.01 / 8.0, 1e-15);
}

TEST(HaltedTrajectory, KeepsTheContourAndItsClosedFormTaskFrame) {
  const auto motion = circle();
  const HaltedTrajectory halted(motion, 2.0, 0.5);
  const Eigen::Vector2d off(0.063, 0.048);
  EXPECT_DOUBLE_EQ(halted.contour_error(off), (off - Eigen::Vector2d(0.05, 0.05)).norm() - 0.01);
  EXPECT_EQ(&halted.geometry(), motion.get());
  // The frame is the circle's closed form (a CircleTaskFrame), not the slow numerical one.
  EXPECT_NE(dynamic_cast<const CircleTaskFrame*>(make_task_frame(halted).get()), nullptr);
}

TEST(HaltedTrajectory, RejectsANegativeStartOrANonPositiveLength) {
  EXPECT_THROW(HaltedTrajectory(circle(), -1.0, 0.1), std::invalid_argument);
  EXPECT_THROW(HaltedTrajectory(circle(), 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(HaltedTrajectory(circle(), std::nan(""), 0.1), std::invalid_argument);
  EXPECT_THROW(HaltedTrajectory(nullptr, 1.0, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control

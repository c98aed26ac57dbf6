// Foot points near the heart's cusps: the exact (global) foot point is the independent truth.
#include <gtest/gtest.h>

#include "control/contour_error/corner_foot_point.hpp"
#include "control/trajectory/heart_trajectory.hpp"

namespace netmc::control {
namespace {

// Points on the branch just after the top cusp (t = 0), pushed off the path to either side, with
// the warm start where they are: a servo lagging behind a desired point. Across the cusp the
// other branch comes close; for some of these points it is the nearer one.
TEST(CornerFootPoint, FindsTheNearerBranchAcrossACuspThatTheLocalIterationMisses) {
  const HeartTrajectory heart(HeartParameters{});
  int plain_misses = 0;
  for (double after : {0.05, 0.10, 0.15}) {
    for (double offset_m : {-60e-6, 60e-6}) {
      const ReferencePoint p = heart.sample(after);
      const Eigen::Vector2d normal = Eigen::Vector2d(-p.velocity.y(), p.velocity.x()).normalized();
      const Eigen::Vector2d point = p.position + offset_m * normal;
      const double truth = exact_foot_point(heart, point).distance_m;
      for (auto method : {&newton_foot_point, &steffensen_foot_point}) {
        const FootPoint plain = method(heart, point, after, FootPointOptions{});
        const FootPoint checked = corner_checked_foot_point(heart, point, after, method);
        EXPECT_NEAR(checked.distance_m, truth, 1e-9) << after << " " << offset_m;
        EXPECT_GE(checked.iterations, plain.iterations);
        if (plain.distance_m > truth + 1e-6) ++plain_misses;
      }
    }
  }
  EXPECT_GT(plain_misses, 0);  // the case exists: the check is what finds the other branch
}

TEST(CornerFootPoint, AwayFromCornersItIsTheLocalMethod) {
  const HeartTrajectory heart(HeartParameters{});
  const ReferencePoint p = heart.sample(2.5);
  const Eigen::Vector2d point = p.position + Eigen::Vector2d(30e-6, -20e-6);
  const FootPoint plain = steffensen_foot_point(heart, point, 2.49, FootPointOptions{});
  const FootPoint checked = corner_checked_foot_point(heart, point, 2.49, &steffensen_foot_point);
  EXPECT_EQ(checked.time_s, plain.time_s);
  EXPECT_EQ(checked.iterations, plain.iterations);
}

}  // namespace
}  // namespace netmc::control

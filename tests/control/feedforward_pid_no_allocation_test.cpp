// Paper 004's controllers step 20 000 times per simulated second: a cycle must not touch the
// heap. This binary replaces the global operator new to count allocations made while they step.

#include <gtest/gtest.h>

#include <cmath>

#include "control/cross_coupling/feedforward_pid_contouring.hpp"
#include "control/cross_coupling/tustin_cross_coupling.hpp"
#include "control/trajectory/circle_trajectory.hpp"
#include "tests/support/allocation_counter.hpp"

namespace netmc::control {
namespace {

TEST(NoAllocation, FeedforwardPidControllersStepWithoutAllocating) {
  CircleParameters p;
  p.radius_m = 0.05;
  p.period_s = 0.2;
  p.ramp_s = 0.02;
  const CircleTrajectory circle(p);
  for (const char* name : {"ffpid", "ffpid+lpccc", "ffpid+qftccc"}) {
    std::unique_ptr<ContourCompensator> compensator = std::make_unique<NoContourCompensation>();
    if (std::string(name) == "ffpid+lpccc") {
      compensator = std::make_unique<TustinCrossCoupling>(make_low_pass_pid_cross_coupling({}, 5e-5));
    }
    if (std::string(name) == "ffpid+qftccc") compensator = std::make_unique<TustinCrossCoupling>(make_qft_cross_coupling(5e-5));
    auto controller = std::make_unique<FeedforwardPidContouring>(paper004_x_axis_gains(), paper004_y_axis_gains(), 5e-5,
                                                                 make_contour_error_estimator("tangent"),
                                                                 std::move(compensator));
    controller->begin_iteration(circle.sample(0.0).position, 6000);
    const long before = netmc::testing::heap_allocations();
    double sum = 0.0;
    for (std::size_t k = 0; k < 6000; ++k) {  // through the ramps and the hold at rest
      const ReferencePoint reference = circle.sample(5e-5 * static_cast<double>(k));
      sum += controller->step(k, reference, reference.position + Eigen::Vector2d(1e-7, -2e-7)).command.sum();
    }
    EXPECT_EQ(netmc::testing::heap_allocations() - before, 0) << name;
    EXPECT_TRUE(std::isfinite(sum)) << name;
  }
}

}  // namespace
}  // namespace netmc::control

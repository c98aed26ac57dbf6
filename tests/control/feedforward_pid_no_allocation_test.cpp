// Paper 004's controllers step 20 000 times per simulated second: a cycle must not touch the
// heap. This binary replaces the global operator new to count allocations made while they step.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>

#include "control/controller_catalog.hpp"
#include "control/trajectory/circle_trajectory.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace netmc::control {
namespace {

TEST(NoAllocation, FeedforwardPidControllersStepWithoutAllocating) {
  CircleParameters p;
  p.radius_m = 0.05;
  p.period_s = 0.2;
  p.ramp_s = 0.02;
  const CircleTrajectory circle(p);
  ControllerSettings settings;
  settings.estimator = "tangent";
  for (const char* name : {"ffpid", "ffpid+lpccc", "ffpid+qftccc"}) {
    auto controller = make_contour_controller(name, settings, 5e-5, circle);
    controller->begin_iteration(circle.sample(0.0).position, 6000);
    const long before = g_allocations.load();
    double sum = 0.0;
    for (std::size_t k = 0; k < 6000; ++k) {  // through the ramps and the hold at rest
      const ReferencePoint reference = circle.sample(5e-5 * static_cast<double>(k));
      sum += controller->step(k, reference, reference.position + Eigen::Vector2d(1e-7, -2e-7)).command.sum();
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << name;
    EXPECT_TRUE(std::isfinite(sum)) << name;
  }
}

}  // namespace
}  // namespace netmc::control

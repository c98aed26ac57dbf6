// Trajectory initialization filter (thesis eq. 2-67): the exact offset against the closed form
// of the critically damped response and against eq. 2-67 integrated numerically as printed; the
// controller starts with zero error with respect to r_i.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <numbers>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/task_space/task_space_darc.hpp"
#include "control/task_space/task_space_sarc.hpp"
#include "control/task_space/task_space_sliding_variable.hpp"
#include "control/task_space/trajectory_initialization_filter.hpp"

namespace netmc::control {
namespace {

constexpr double kWc = 8.0;
constexpr double kWm = 1.0;

TEST(TrajectoryInitializationFilter, ContourReferenceIsTheCriticallyDampedResponse) {
  TrajectoryInitializationFilter filter(kWc, kWm);
  const double rc0 = 0.01;  // thesis case B: r_ci(0) = 0.01 m, at rest
  filter.start({rc0, 0.0}, {0.0, 0.0});
  for (double t : {0.0, 0.05, 0.125, 0.4, 1.0, 3.0}) {
    const double expected = rc0 * (1.0 + kWc * t) * std::exp(-kWc * t);  // r_cd = 0, r_ci = z_c
    const FilterOffset z = filter.offset(t);
    EXPECT_NEAR(z.value[0], expected, 1e-15) << t;
    EXPECT_NEAR(z.rate[0], -rc0 * kWc * kWc * t * std::exp(-kWc * t), 1e-14) << t;
  }
  EXPECT_THROW(TrajectoryInitializationFilter(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(TrajectoryInitializationFilter(8.0, -1.0), std::invalid_argument);
}

// r_md(t) of a motion that speeds up and wiggles, and its derivatives.
double desired(double t) { return 0.06283 + 0.6 * t + 0.02 * std::sin(3.0 * t); }
double desired_rate(double t) { return 0.6 + 0.06 * std::cos(3.0 * t); }
double desired_acceleration(double t) { return -0.18 * std::sin(3.0 * t); }

TEST(TrajectoryInitializationFilter, TangentialReferenceSolvesEquation267AndConvergesToTheDesired) {
  // Eq. 2-67 as printed, by RK4: r'' = -2 w r' - w^2 r + r_md'' + 2 w r_md' + w^2 r_md, from
  // r_mi(0) = r_m(q(0)) = 0, r_mi'(0) = 0.
  double r = 0.0, v = 0.0;
  const auto acceleration = [](double t, double position, double velocity) {
    return -2.0 * kWm * velocity - kWm * kWm * position + desired_acceleration(t) +
           2.0 * kWm * desired_rate(t) + kWm * kWm * desired(t);
  };
  TrajectoryInitializationFilter filter(kWc, kWm);
  filter.start({0.0, r - desired(0.0)}, {0.0, v - desired_rate(0.0)});
  const double dt = 1e-3;
  double t = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double k1r = v, k1v = acceleration(t, r, v);
    const double k2r = v + 0.5 * dt * k1v, k2v = acceleration(t + 0.5 * dt, r + 0.5 * dt * k1r, v + 0.5 * dt * k1v);
    const double k3r = v + 0.5 * dt * k2v, k3v = acceleration(t + 0.5 * dt, r + 0.5 * dt * k2r, v + 0.5 * dt * k2v);
    const double k4r = v + dt * k3v, k4v = acceleration(t + dt, r + dt * k3r, v + dt * k3v);
    r += dt / 6.0 * (k1r + 2 * k2r + 2 * k3r + k4r);
    v += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    t += dt;
    if (k % 500 == 499) {
      const FilterOffset z = filter.offset(t);
      EXPECT_NEAR(desired(t) + z.value[1], r, 1e-10) << t;
      EXPECT_NEAR(desired_rate(t) + z.rate[1], v, 1e-10) << t;
    }
  }
  // r_mi -> r_md.
  EXPECT_LT(std::abs(filter.offset(t).value[1]), 1e-6);
  EXPECT_LT(std::abs(r - desired(t)), 1e-6);
}

// Thesis case B (eq. 2-66): clockwise circle r = 4 cm about (0, 5 cm), stage at rest at (0, 0).
CircleTrajectory case_b() {
  CircleParameters p;
  p.center = {0.0, 0.05};
  p.radius_m = 0.04;
  p.period_s = 2.0 * std::numbers::pi / 15.0;
  p.clockwise = true;
  return CircleTrajectory(p);
}

TEST(TrajectoryInitializationFilter, ControllersStartWithZeroErrorWithRespectToTheFilteredReference) {
  const CircleTrajectory circle = case_b();
  const Eigen::Vector2d start(0.0, 0.0);
  InitializationFilterSettings on;
  on.enabled = true;
  TaskSpaceSarc filtered(SarcGains{}, 2e-4, make_task_frame(circle), on);
  TaskSpaceSarc raw(SarcGains{}, 2e-4, make_task_frame(circle));
  TaskSpaceDarc filtered_darc(DarcGains{}, 2e-4, make_task_frame(circle), on);
  for (ContourController* c : std::initializer_list<ContourController*>{&filtered, &raw, &filtered_darc}) {
    c->begin_iteration(start, 100);
  }
  const auto reference = circle.sample(0.0);
  const ContouringCycle a = filtered.step(0, reference, start);
  const ContouringCycle b = raw.step(0, reference, start);
  const ContouringCycle c = filtered_darc.step(0, reference, start);
  // rc - r_ci = 0 and s = 0 at rest: no feedback at all (friction of zero velocity is zero).
  EXPECT_EQ(a.estimate.contour_error, 0.0);
  EXPECT_LT(a.command.norm(), 1e-12);
  EXPECT_EQ(c.estimate.contour_error, 0.0);
  EXPECT_LT(c.command.norm(), 1e-12);
  // Unfiltered, the 1 cm contour error and the 1/4 turn along the contour ask for far beyond 8 V.
  EXPECT_NEAR(b.estimate.contour_error, 0.01, 1e-12);
  EXPECT_GT(b.command.norm(), 100.0);
  // The next cycle, still at rest: the error is rc - r_ci(h), with r_ci of the filter's clock.
  const double x = kWc * 2e-4;
  EXPECT_NEAR(filtered.step(1, circle.sample(2e-4), start).estimate.contour_error,
              0.01 * (1.0 - (1.0 + x) * std::exp(-x)), 1e-15);
}

TEST(TrajectoryInitializationFilter, TangentialErrorStaysContinuousWhenRmiFallsHalfARevolutionBehind) {
  // Case B: z_m(0) = +R pi/2 (the stage's foot point is a quarter turn ahead along the motion),
  // z_m'(0) = -0.6 m/s; z_m dips to about -0.176 m at t = 1.1 s, beyond half the perimeter
  // (0.126 m). A stage exactly on r_i must read zero error throughout.
  const CircleTrajectory circle = case_b();
  const double radius = 0.04, h = 2e-4;
  InitializationFilterSettings on;
  on.enabled = true;
  TaskSpaceSlidingVariable sliding({100.0, 30.0}, h, make_task_frame(circle), on);
  TrajectoryInitializationFilter filter(kWc, kWm);
  filter.start({0.01, radius * std::numbers::pi / 2.0}, {0.0, -0.6});
  double deepest = 0.0;
  for (std::size_t k = 0; k < 15000; ++k) {
    const double t = static_cast<double>(k) * h;
    const FilterOffset z = filter.offset(t);
    deepest = std::min(deepest, z.value[1]);
    // On r_i: radius R + z_c, and z_m of arc along the (clockwise) motion ahead of the desired point.
    const double angle = -15.0 * t - z.value[1] / radius;
    const Eigen::Vector2d q = Eigen::Vector2d(0.0, 0.05) + (radius + z.value[0]) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const SlidingState state = sliding.update(k, circle.sample(t), q);
    ASSERT_NEAR(state.error[0], 0.0, 1e-12) << t;
    ASSERT_NEAR(state.error[1], 0.0, 1e-9) << t;
  }
  EXPECT_LT(deepest, -0.5 * 2.0 * std::numbers::pi * radius);  // it did cross half a revolution
}

TEST(TrajectoryInitializationFilter, NeedsTheGlobalTaskFrame) {
  InitializationFilterSettings on;
  on.enabled = true;
  EXPECT_THROW(TaskSpaceSarc(SarcGains{}, 2e-4, nullptr, on), std::invalid_argument);
  EXPECT_THROW(TaskSpaceDarc(DarcGains{}, 2e-4, nullptr, on), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control

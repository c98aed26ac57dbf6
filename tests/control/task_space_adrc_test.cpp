// Task-space ADRC on an ideal plant whose task coordinates are linear (rc = y, rm = x): each task
// coordinate is then an exact double integrator, so the observer and the loop have closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>

#include "control/task_space/task_space_adrc.hpp"

namespace netmc::control {
namespace {

constexpr double kH = 2e-4;

// rc = y, rm = x: J = [[0, 1], [1, 0]], constant.
class PlaneTaskFrame final : public TaskFrame {
 public:
  TaskCoordinates at(const Eigen::Vector2d& q) const override {
    TaskCoordinates r;
    r.rc = q.y();
    r.rm = q.x();
    r.jacobian << 0.0, 1.0, 1.0, 0.0;
    return r;
  }
  double perimeter_m() const override { return 0.0; }
};

// Nominal model = the plant: masses only, no damping or friction.
GtcfAdrcGains ideal_gains(Discretization discretization) {
  GtcfAdrcGains gains;
  gains.damping.setZero();
  gains.coulomb.setZero();
  gains.discretization = discretization;
  return gains;
}

// Cartesian double integrator M q'' = u + M d, the command held over each period (exact).
struct IdealStage {
  Eigen::Vector2d mass{0.1, 0.55};
  Eigen::Vector2d disturbance = Eigen::Vector2d::Zero();  // acceleration [m/s^2]
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  void step(const Eigen::Vector2d& command) {
    const Eigen::Vector2d a = command.cwiseQuotient(mass) + disturbance;
    position += kH * velocity + 0.5 * kH * kH * a;
    velocity += kH * a;
  }
};

// The desired motion: along x at 0.2 m/s on the line y = 0.
ReferencePoint line_reference(double t) {
  ReferencePoint p;
  p.position = {0.2 * t, 0.0};
  p.velocity = {0.2, 0.0};
  return p;
}

class TaskSpaceAdrcObserver : public ::testing::TestWithParam<Discretization> {};

TEST_P(TaskSpaceAdrcObserver, EstimatesAConstantTaskDisturbanceExactly) {
  // A constant Cartesian acceleration d is the task disturbance J d = [d_y, d_x]. At the loop's
  // equilibrium (moving at the reference speed, no observer error) z3 = -u_t = J d exactly, for
  // either discretization; the loop then tracks with zero error despite d.
  TaskSpaceAdrc adrc(ideal_gains(GetParam()), kH, std::make_shared<PlaneTaskFrame>());
  IdealStage stage;
  stage.disturbance = {-3.0, 2.0};
  adrc.begin_iteration(stage.position, 0);
  for (std::size_t k = 0; k < 10000; ++k) {  // 2 s: the slowest pole (w_m = 100) decays e^-200
    stage.step(adrc.step(k, line_reference(static_cast<double>(k) * kH), stage.position).command);
  }
  EXPECT_NEAR(adrc.observer(0).disturbance(), 2.0, 1e-9);   // contour (y)
  EXPECT_NEAR(adrc.observer(1).disturbance(), -3.0, 1e-9);  // tangential (x)
  EXPECT_NEAR(stage.position.y(), 0.0, 1e-12);
  EXPECT_NEAR(stage.position.x(), 0.2 * 10000 * kH, 1e-11);
}

INSTANTIATE_TEST_SUITE_P(BothDiscretizations, TaskSpaceAdrcObserver,
                         ::testing::Values(Discretization::forward_euler, Discretization::zero_order_hold));

// Contour step: start 1 mm off the contour with the reference at rest. Returns rc(k h).
std::vector<double> contour_step(Discretization discretization, std::size_t steps) {
  TaskSpaceAdrc adrc(ideal_gains(discretization), kH, std::make_shared<PlaneTaskFrame>());
  IdealStage stage;
  stage.position = {0.0, 1e-3};
  adrc.begin_iteration(stage.position, 0);
  ReferencePoint rest;
  std::vector<double> rc;
  for (std::size_t k = 0; k < steps; ++k) {
    rc.push_back(stage.position.y());
    stage.step(adrc.step(k, rest, stage.position).command);
  }
  return rc;
}

TEST(TaskSpaceAdrc, ContourStepHasTheDesignedDoublePole) {
  const double w = GtcfAdrcGains{}.loop_bandwidth[0];
  constexpr std::size_t kSteps = 250;  // 50 ms = 15 time constants

  // Exact-model observer started on the true state: z = x at every step, z3 = 0, so the loop is
  // the sampled double integrator under u = -w^2 rc - 2 w rc' (second method: its recursion).
  const auto zoh = contour_step(Discretization::zero_order_hold, kSteps);
  Eigen::Matrix2d phi;
  phi << 1.0, kH, 0.0, 1.0;
  const Eigen::Vector2d gamma(0.5 * kH * kH, kH);
  Eigen::Vector2d x(1e-3, 0.0);
  for (std::size_t k = 0; k < kSteps; ++k) {
    ASSERT_NEAR(zoh[k], x[0], 1e-15) << "k = " << k;
    x = phi * x + gamma * (-w * w * x[0] - 2.0 * w * x[1]);
  }

  // Both observers against the continuous design (s + w)^2: rc = rc0 (1 + w t) e^(-w t), within
  // the sampling's O(w h) = 6 %.
  const auto euler = contour_step(Discretization::forward_euler, kSteps);
  for (std::size_t k = 0; k < kSteps; ++k) {
    const double t = static_cast<double>(k) * kH;
    const double design = 1e-3 * (1.0 + w * t) * std::exp(-w * t);
    EXPECT_NEAR(zoh[k], design, 0.03e-3) << "k = " << k;
    EXPECT_NEAR(euler[k], design, 0.06e-3) << "k = " << k;
  }
  // Settled: below 0.1 % after 15 time constants, for both.
  EXPECT_LT(std::abs(zoh.back()), 1e-6);
  EXPECT_LT(std::abs(euler.back()), 1e-6);
}

// Contour step on a stage that applies each command `plant_delay` periods late; the largest
// observer error |z1 - rc| + |z3| seen over the step.
double observer_error_under_delay(unsigned plant_delay, unsigned observer_input_delay) {
  GtcfAdrcGains gains = ideal_gains(Discretization::zero_order_hold);
  gains.loop_bandwidth = {100.0, 100.0};  // slow enough to stay stable with 3 periods of delay
  gains.observer_input_delay = observer_input_delay;
  TaskSpaceAdrc adrc(gains, kH, std::make_shared<PlaneTaskFrame>());
  IdealStage stage;
  stage.position = {0.0, 1e-3};
  adrc.begin_iteration(stage.position, 0);
  std::deque<Eigen::Vector2d> in_flight(plant_delay, Eigen::Vector2d::Zero());
  double worst = 0.0;
  for (std::size_t k = 0; k < 500; ++k) {
    // z(k), the observer's prediction of this period's state, against the true rc(k).
    worst = std::max(worst, std::abs(adrc.observer(0).position() - stage.position.y()) +
                                std::abs(adrc.observer(0).disturbance()));
    in_flight.push_back(adrc.step(k, ReferencePoint{}, stage.position).command);
    stage.step(in_flight.front());
    in_flight.pop_front();
  }
  return worst;
}

TEST(TaskSpaceAdrc, ObserverInputDelayMatchingThePlantsKeepsTheModelExact) {
  // Fed the command that acts now, the exact-model observer stays on the true state with no
  // disturbance estimate (errors at rounding level); fed this period's command while the plant
  // applies one 3 periods old, the lateness shows up as a disturbance (paper 001, eq. 6).
  EXPECT_LT(observer_error_under_delay(3, 3), 1e-12);
  EXPECT_LT(observer_error_under_delay(0, 0), 1e-12);
  EXPECT_GT(observer_error_under_delay(3, 0), 1.0);  // m/s^2: the step's command is ~10 m/s^2
}

TEST(TaskSpaceAdrc, RejectsBadGainsAndAMissingFrame) {
  GtcfAdrcGains bad;
  bad.loop_bandwidth[0] = 0.0;
  EXPECT_THROW(TaskSpaceAdrc(bad, kH, std::make_shared<PlaneTaskFrame>()), std::invalid_argument);
  bad = GtcfAdrcGains{};
  bad.observer_bandwidth[1] = -1.0;
  EXPECT_THROW(TaskSpaceAdrc(bad, kH, std::make_shared<PlaneTaskFrame>()), std::invalid_argument);
  EXPECT_THROW(TaskSpaceAdrc(GtcfAdrcGains{}, kH, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control

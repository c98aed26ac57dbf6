// Task-space DIARC (thesis ch. 3): the filter H_f against the closed-form step response; with
// only parametric uncertainty the least-squares estimator finds the true masses and offsets and
// the contour error goes to zero; every estimate stays inside its box.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/task_space/task_space_diarc.hpp"
#include "tests/control/thesis_model_support.hpp"

namespace netmc::control {
namespace {

constexpr double kH = 2e-4;

TEST(TaskSpaceDiarc, FilterFollowsTheSecondOrderStepResponse) {
  const double cutoff_hz = 20.0, zeta = 0.7;
  SecondOrderLowPass filter(cutoff_hz, zeta, kH);
  const double w = 2.0 * std::numbers::pi * cutoff_hz, wd = w * std::sqrt(1.0 - zeta * zeta);
  for (int k = 1; k <= 1000; ++k) {
    filter.step(1.0);  // the trapezoid reads the first period as a ramp 0 -> 1: a h/2 delay
    const double t = k * kH - 0.5 * kH;
    const double decay = std::exp(-zeta * w * t);
    const double y = 1.0 - decay * (std::cos(wd * t) + zeta / std::sqrt(1.0 - zeta * zeta) * std::sin(wd * t));
    const double dy = decay * w / std::sqrt(1.0 - zeta * zeta) * std::sin(wd * t);
    ASSERT_NEAR(filter.value(), y, 2e-4) << k;
    ASSERT_NEAR(filter.derivative(), dy, 2e-4 * w) << k;
  }
}

TEST(TaskSpaceDiarc, EstimatesStayInsideTheirBoxes) {
  CircleTrajectory circle({{0.0, 0.0}, 0.04, 0.4});
  DiarcGains gains;
  TaskSpaceDiarc diarc(gains, kH, make_task_frame(circle));
  diarc.begin_iteration(circle.sample(0.0).position, 5000);
  for (std::size_t k = 0; k < 5000; ++k) {
    const double t = static_cast<double>(k) * kH;
    const ContouringCycle out = diarc.step(k, circle.sample(t), 1.05 * circle.sample(t - 0.01).position);
    ASSERT_TRUE(out.command.allFinite());
    for (int i = 0; i < 8; ++i) {
      ASSERT_GE(diarc.parameter_estimate()[i], gains.lower[i]) << i << " at " << k;
      ASSERT_LE(diarc.parameter_estimate()[i], gains.upper[i]) << i << " at " << k;
    }
    ASSERT_LE(diarc.disturbance_estimate().cwiseAbs().maxCoeff(), 1.0);
  }
  EXPECT_EQ(diarc.disturbance_estimate().cwiseAbs().maxCoeff(), 1.0);  // pushed onto its bound
}

using thesis_support::exp_i_ellipse;
using thesis_support::ModelPlant;

TEST(TaskSpaceDiarc, LeastSquaresFindsTheTrueParametersWithOnlyParametricUncertainty) {
  // Thesis Exp I ellipse (eq. 3-48), 8 revolutions, the thesis's C2 gains.
  const EllipseTrajectory ellipse = exp_i_ellipse(8.0);
  const DiarcGains gains;
  ModelPlant plant;
  plant.theta << 0.15, 0.62, 0.4, 0.45, 0.12, 0.2, 0.1, -0.15;  // inside the box (3-47)
  plant.q = ellipse.sample(0.0).position;
  plant.v = ellipse.sample(0.0).velocity;
  TaskSpaceDiarc diarc(gains, kH, make_task_frame(ellipse));
  diarc.begin_iteration(plant.q, 0);
  const auto cycles = static_cast<std::size_t>(ellipse.duration_s() / kH);
  const auto period = static_cast<std::size_t>(ellipse.period_s() / kH);
  double first_square = 0.0, last_square = 0.0;
  for (std::size_t k = 0; k < cycles; ++k) {
    const ContouringCycle out = diarc.step(k, ellipse.sample(static_cast<double>(k) * kH), plant.q);
    const double error = ellipse.contour_error(plant.q);
    if (k < period) first_square += error * error;
    if (k >= cycles - period) last_square += error * error;
    plant.advance(out.command, kH);
  }
  // Measured: 1.43 um in the first revolution, 0.14 um in the last.
  EXPECT_LT(std::sqrt(last_square), 0.2 * std::sqrt(first_square));
  // Measured: M1, M2, dn1, dn2 right to three decimals; B and A (whose columns v and S_f(v) are nearly
  // parallel on this motion) still converging: B2 0.30 -> 0.41 (true 0.45).
  const ParameterVector& theta = diarc.parameter_estimate();
  for (int i : {0, 1}) EXPECT_NEAR(theta[i], plant.theta[i], 0.01 * plant.theta[i]) << "M" << i + 1;
  for (int i : {6, 7}) EXPECT_NEAR(theta[i], plant.theta[i], 0.005) << "dn" << i - 5;
  EXPECT_LT((theta - plant.theta).norm(), 0.3 * (gains.initial_estimate - plant.theta).norm());
}

}  // namespace
}  // namespace netmc::control

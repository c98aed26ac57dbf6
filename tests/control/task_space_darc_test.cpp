// Task-space DARC (thesis ch. 3): the projection keeps every parameter estimate inside its box;
// with only parametric uncertainty (the plant has the controller's model structure, another
// theta) the contour error goes to zero and theta_hat moves towards the true theta.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/trajectory/circle_trajectory.hpp"
#include "control/task_space/task_space_darc.hpp"
#include "tests/control/thesis_model_support.hpp"

namespace netmc::control {
namespace {

constexpr double kH = 2e-4;

TEST(TaskSpaceDarc, ProjectionKeepsEveryParameterInsideItsBox) {
  CircleTrajectory circle({{0.0, 0.0}, 0.04, 0.4});
  DarcGains gains;
  gains.adaptation *= 100.0;  // push hard
  TaskSpaceDarc darc(gains, kH, make_task_frame(circle));
  darc.begin_iteration(circle.sample(0.0).position, 5000);
  // The measured point stays 5 % outside and behind for a long time: s stays large.
  int at_bound = 0;
  for (std::size_t k = 0; k < 5000; ++k) {
    const auto reference = circle.sample(static_cast<double>(k) * kH);
    const ContouringCycle out = darc.step(k, reference, 1.05 * circle.sample(static_cast<double>(k) * kH - 0.01).position);
    ASSERT_TRUE(out.command.allFinite());
    const ParameterVector& theta = darc.parameter_estimate();
    for (int i = 0; i < 8; ++i) {
      ASSERT_GE(theta[i], gains.lower[i]) << i << " at " << k;
      ASSERT_LE(theta[i], gains.upper[i]) << i << " at " << k;
    }
  }
  for (int i = 0; i < 8; ++i) {
    const double theta = darc.parameter_estimate()[i];
    at_bound += (theta == gains.lower[i] || theta == gains.upper[i]) ? 1 : 0;
  }
  EXPECT_GE(at_bound, 2);  // it did push some elements onto their faces
  DarcGains outside;
  outside.initial_estimate[0] = 0.3;  // above theta_max = 0.25
  EXPECT_THROW(TaskSpaceDarc(outside, kH, nullptr), std::invalid_argument);
}

using thesis_support::exp_i_ellipse;
using thesis_support::ModelPlant;

TEST(TaskSpaceDarc, WithOnlyParametricUncertaintyTheContourErrorVanishesAndThetaHatLearns) {
  // Thesis Exp I ellipse (eq. 3-48): x = 0.2 sin 4t, y = 0.1 - 0.1 cos 4t, 8 revolutions.
  const EllipseTrajectory ellipse = exp_i_ellipse(8.0);
  // Gamma = 1e4 throughout: with the thesis's 10 for the physical parameters the adaptation
  // rate Gamma Phi^T J^-1 s is ~1e-3 per second once s is small, too slow to see in seconds.
  DarcGains gains;
  gains.adaptation.setConstant(1e4);
  ModelPlant plant;
  plant.theta << 0.15, 0.62, 0.4, 0.45, 0.12, 0.2, 0.1, -0.15;  // inside the box (3-47)
  plant.q = ellipse.sample(0.0).position;
  plant.v = ellipse.sample(0.0).velocity;  // on the motion from the start
  TaskSpaceDarc darc(gains, kH, make_task_frame(ellipse));
  darc.begin_iteration(plant.q, 0);

  // The model's error along the desired motion, Phi_c(q_d'', q_d') (theta_hat - theta): the
  // directions of theta that this motion excites.
  const auto model_error = [&](double t, const ParameterVector& estimate) {
    const ReferencePoint r = ellipse.sample(t);
    return (darc_regressor(r.acceleration, r.velocity, gains.friction_slope) * (estimate - plant.theta)).squaredNorm();
  };
  const auto cycles = static_cast<std::size_t>(ellipse.duration_s() / kH);
  const auto period = static_cast<std::size_t>(ellipse.period_s() / kH);
  double first_square = 0.0, last_square = 0.0, initial_model = 0.0, final_model = 0.0;
  for (std::size_t k = 0; k < cycles; ++k) {
    const double t = static_cast<double>(k) * kH;
    const ContouringCycle out = darc.step(k, ellipse.sample(t), plant.q);
    const double error = ellipse.contour_error(plant.q);  // exact, independent of the controller
    if (k < period) {
      first_square += error * error;
      initial_model += model_error(t, gains.initial_estimate);
    }
    if (k >= cycles - period) {
      last_square += error * error;
      final_model += model_error(t, darc.parameter_estimate());
    }
    plant.advance(out.command, kH);
  }
  // Measured: 0.46 um in the first revolution, 0.058 um in the last.
  const double first_rms = std::sqrt(first_square / static_cast<double>(period));
  const double last_rms = std::sqrt(last_square / static_cast<double>(period));
  EXPECT_LT(last_rms, 0.2 * first_rms);
  EXPECT_LT(last_rms, 0.1e-6);
  // Measured: model error 0.26 V rms at theta_hat(0), 0.003 V in the last revolution;
  // |theta_hat - theta| 0.28 -> 0.05.
  EXPECT_LT(std::sqrt(final_model / initial_model), 0.1);
  const ParameterVector initial_error = gains.initial_estimate - plant.theta;
  const ParameterVector final_error = darc.parameter_estimate() - plant.theta;
  EXPECT_LT(final_error.norm(), 0.3 * initial_error.norm());
  for (int i : {0, 1, 3, 7}) {  // the largest initial errors: M1, M2, B2, dn2
    EXPECT_LT(std::abs(final_error[i]), 0.5 * std::abs(initial_error[i])) << "theta " << i + 1;
  }
}

}  // namespace
}  // namespace netmc::control

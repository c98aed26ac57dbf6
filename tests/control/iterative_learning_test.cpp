// Learning laws against closed forms: error reduction on a repeated task, the forgetting-factor
// fixed point, the zero-phase Q-filter, and PID cross coupling.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <numbers>

#include "control/cross_coupling/iterative_learning_cross_coupling.hpp"
#include "control/cross_coupling/pid_cross_coupling.hpp"
#include "control/cross_coupling/zero_phase_low_pass.hpp"

namespace netmc::control {
namespace {

// Repeated task on y(k+1) = 0.2 y(k) + u(k), Markov parameters 0.2^i. Learning with one sample
// of lead contracts the max-norm of the error by at most |1 - kcp| + kcp * 0.2/(1 - 0.2) = 0.625
// per iteration (kcp = 0.5), so the error must fall at least that fast.
std::vector<double> run_repeated_task(IterativeLearningCrossCoupling& ilc, int iterations) {
  const std::size_t n = 200;
  std::vector<double> reference(n);
  for (std::size_t k = 0; k < n; ++k) reference[k] = std::sin(0.05 * static_cast<double>(k));
  std::vector<double> max_by_iteration;
  for (int j = 0; j < iterations; ++j) {
    ilc.begin_iteration(n);
    double y = 0.0;
    std::vector<double> errors(n);
    for (std::size_t k = 0; k < n; ++k) {
      errors[k] = reference[k] - y;
      const double u = ilc.command(k, errors[k]);
      y = 0.2 * y + u;
    }
    ilc.end_iteration();
    double worst = 0.0;
    for (std::size_t k = 1; k < n; ++k) worst = std::max(worst, std::abs(errors[k]));
    max_by_iteration.push_back(worst);
  }
  return max_by_iteration;
}

TEST(IterativeLearning, ReducesTheErrorOfARepeatedTask) {
  IterativeLearningGains gains;
  gains.kcp = 0.5;
  gains.kcd = 0.0;
  gains.lead_samples = 1;
  IterativeLearningCrossCoupling ilc(gains, 0.001);
  const auto curve = run_repeated_task(ilc, 40);
  for (std::size_t j = 1; j < curve.size(); ++j) EXPECT_LE(curve[j], 0.625 * curve[j - 1] + 1e-15);
  EXPECT_LT(curve.back(), 1e-7 * curve.front());
  EXPECT_EQ(ilc.completed_iterations(), 40u);
}

TEST(IterativeLearning, FirstIterationIsPlainFeedback) {
  IterativeLearningCrossCoupling ilc(IterativeLearningGains{}, 0.005);
  ilc.begin_iteration(10);
  for (std::size_t k = 0; k < 10; ++k) EXPECT_EQ(ilc.command(k, 1.0), 0.0);
}

TEST(IterativeLearning, PaperLawOnAKnownErrorSequence) {
  // eq. 14: u_j(k) = u_j-1(k) + kcp eps(k) + kcd (eps(k) - eps(k-1)), eps(-1) = 0.
  IterativeLearningCrossCoupling ilc(IterativeLearningGains{}, 0.005);
  const std::vector<double> eps{0.0, 1e-3, 3e-3, 2e-3};
  ilc.begin_iteration(4);
  for (std::size_t k = 0; k < 4; ++k) ilc.command(k, eps[k]);
  ilc.end_iteration();
  ilc.begin_iteration(4);
  const std::vector<double> expected{0.0, 40 * 1e-3 + 40 * 1e-3, 40 * 3e-3 + 40 * 2e-3,
                                     40 * 2e-3 - 40 * 1e-3};
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(ilc.learned_command()[k], expected[k], 1e-15);
}

TEST(IterativeLearning, ForgettingFactorBoundsTheLearnedCommand) {
  // With a constant error e every iteration, u_j = (1-g) u_j-1 + kcp e converges to kcp e / g.
  IterativeLearningGains gains;
  gains.kcp = 2.0;
  gains.kcd = 0.0;
  gains.forgetting = 0.1;
  IterativeLearningCrossCoupling ilc(gains, 0.005);
  for (int j = 0; j < 400; ++j) {
    ilc.begin_iteration(5);
    for (std::size_t k = 0; k < 5; ++k) ilc.command(k, 0.5);
    ilc.end_iteration();
  }
  ilc.begin_iteration(5);
  EXPECT_NEAR(ilc.learned_command()[2], 2.0 * 0.5 / 0.1, 1e-9);
  EXPECT_THROW(IterativeLearningCrossCoupling({40, 40, 1.0}, 0.005), std::invalid_argument);
}

TEST(ZeroPhaseLowPass, KeepsConstantsAndSymmetryAndAttenuatesNoise) {
  const ZeroPhaseLowPass filter(5.0, 0.005);
  std::vector<double> constant(50, 3.0);
  filter.apply(constant);
  for (double v : constant) EXPECT_NEAR(v, 3.0, 1e-12);

  // A pulse centred at 100 stays centred (no phase lag): the output is symmetric about it.
  std::vector<double> pulse(201, 0.0);
  pulse[100] = 1.0;
  filter.apply(pulse);
  for (int i = 1; i < 60; ++i) EXPECT_NEAR(pulse[100 - i], pulse[100 + i], 1e-10);
  EXPECT_EQ(std::max_element(pulse.begin(), pulse.end()) - pulse.begin(), 100);

  // Nyquist-rate alternation: each pass scales it by (1-p)/(1+p).
  std::vector<double> alternating(400);
  for (std::size_t k = 0; k < alternating.size(); ++k) alternating[k] = (k % 2 ? 1.0 : -1.0);
  filter.apply(alternating);
  const double p = std::exp(-2 * std::numbers::pi * 5.0 * 0.005);
  EXPECT_NEAR(std::abs(alternating[200]), std::pow((1 - p) / (1 + p), 2), 1e-9);
}

TEST(PidCrossCoupling, DiscreteLawOnAKnownSequence) {
  PidCrossCoupling pid({500.0, 10.0, 50.0}, 0.005);
  pid.begin_iteration(3);
  EXPECT_NEAR(pid.command(0, 1e-3), 500 * 1e-3 + 10 * 0.005 * 1e-3 + 50 * 1e-3, 1e-15);
  EXPECT_NEAR(pid.command(1, 3e-3), 500 * 3e-3 + 10 * 0.005 * 4e-3 + 50 * 2e-3, 1e-15);
  pid.begin_iteration(3);  // a new iteration forgets the integral and the previous error
  EXPECT_NEAR(pid.command(0, 1e-3), 500 * 1e-3 + 10 * 0.005 * 1e-3 + 50 * 1e-3, 1e-15);
}

}  // namespace
}  // namespace netmc::control

// Paper 002's building blocks: the data-model estimators (eq. 11-14) against a plant that is
// exactly their data model, and the reaching law (eq. 18-20) against the reaching conditions.

#include <gtest/gtest.h>

#include <cmath>

#include "control/data_driven/data_model_estimator.hpp"
#include "control/data_driven/terminal_sliding_mode.hpp"
#include "netsim/random_stream.hpp"

namespace netmc::control {
namespace {

// y(k+1) = y(k) + Phi du(k) + Psi dd(k) with constant Phi, Psi (eq. 9 with known derivatives).
struct KnownDataModel {
  double phi, psi;
};

TEST(DataModelEstimator, PhiConvergesToTheTrueDerivativeUnderExcitation) {
  const KnownDataModel plant{30.0, 10.0};
  DataModelEstimator estimator({});
  netsim::RandomStream random(7);
  double previous_du = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const double dy = plant.phi * previous_du;  // no disturbance
    estimator.update(dy, previous_du);
    previous_du = random.uniform(-1.0, 1.0);
  }
  EXPECT_NEAR(estimator.phi(), plant.phi, 0.05);
  EXPECT_NEAR(estimator.disturbance_increment(), 0.0, 1e-3);
}

TEST(DataModelEstimator, PredictionErrorShrinksWithAnUnknownDisturbance) {
  // A slow sinusoidal disturbance the estimator does not see: kappa must come to explain dy.
  const KnownDataModel plant{30.0, 10.0};
  DataModelEstimator estimator({});
  netsim::RandomStream random(11);
  double previous_du = 0.0, previous_d = 0.0;
  double early = 0.0, late = 0.0, late_dy = 0.0;
  for (int k = 1; k <= 4000; ++k) {
    const double d = 0.2 * std::sin(2.0 * 3.141592653589793 * k / 500.0);
    const double dy = plant.phi * previous_du + plant.psi * (d - previous_d);
    const double predicted = estimator.psi() * estimator.disturbance_increment() + estimator.phi() * previous_du;
    const double residual = std::abs(dy - predicted);
    if (k <= 200) early += residual;
    if (k > 3800) {
      late += residual;
      late_dy += std::abs(dy);
    }
    estimator.update(dy, previous_du);
    previous_du = 0.05 * random.uniform(-1.0, 1.0);
    previous_d = d;
  }
  EXPECT_LT(late, 0.5 * early);
  EXPECT_LT(late, 0.5 * late_dy);
}

TEST(DataModelEstimator, ResetsFollowSection32) {
  DataModelEstimatorGains gains;
  gains.phi_initial = 18.0;
  DataModelEstimator estimator(gains);
  estimator.update(100.0, 1.0);  // moves Phi^ away from 18
  ASSERT_NE(estimator.phi(), 18.0);
  estimator.update(1.0, 0.0);  // |du| <= epsilon: back to Phi^(1)
  EXPECT_EQ(estimator.phi(), 18.0);
  // |dd^| >= 2 d0: dd^ and d^ back to 0.
  gains.disturbance_bound = 1e-3;
  DataModelEstimator small_bound(gains);
  small_bound.update(1000.0, 0.0);
  EXPECT_EQ(small_bound.disturbance_increment(), 0.0);
  EXPECT_EQ(small_bound.disturbance(), 0.0);
}

TEST(DataModelEstimator, RejectsGainsOutsideTheirRanges) {
  DataModelEstimatorGains gains;
  gains.eta = 1.5;
  EXPECT_THROW(DataModelEstimator{gains}, std::invalid_argument);
  gains = {};
  gains.rho = 0.0;
  EXPECT_THROW(DataModelEstimator{gains}, std::invalid_argument);
}

TEST(TerminalSlidingMode, SlidingVariableIsEquation17) {
  TerminalSlidingModeGains g;  // paper 002's C4: lambda1 0.3, lambda2 0.2, alpha 5/7, beta 0.75
  const TerminalSlidingMode mode(g, 1e-3);
  const double e = 3.0, previous = -2.0;
  const double expected = 0.3 * 3.0 + 0.2 * -std::pow(2.0, 5.0 / 7.0) - 0.3 * 0.25 * -2.0;
  EXPECT_NEAR(mode.sliding_variable(e, previous), expected, 1e-14);
  EXPECT_EQ(signed_power(-8.0, 1.0 / 3.0), -2.0);
}

TEST(TerminalSlidingMode, ReachingLawMeetsTheReachingConditions) {
  const TerminalSlidingModeGains g;
  const TerminalSlidingMode mode(g, 1e-3);
  // Outside the quasi-sliding band |s| <= lambda cosh(delta2 s) / (1 + E1) (~0.03 here), eq. 65-70:
  // E1 in (0, 1), E2 >= lambda, (s(k+1) - s(k)) sgn s < 0 and (s(k+1) + s(k)) sgn s > 0.
  for (double magnitude = 0.05; magnitude < 1e5; magnitude *= 1.3) {
    for (double s : {magnitude, -magnitude}) {
      EXPECT_GT(mode.e1(s), 0.0);
      EXPECT_LT(mode.e1(s), 1.0);
      EXPECT_GE(mode.e2(s), g.lambda);
      const double next = mode.next_sliding_variable(s);
      const double sign = s > 0 ? 1.0 : -1.0;
      EXPECT_LT((next - s) * sign, 0.0) << s;
      EXPECT_GT((next + s) * sign, 0.0) << s;
    }
  }
  // Inside the band the law only holds s at the band: |s(k+1)| <= lambda cosh(delta2 s).
  EXPECT_LE(std::abs(mode.next_sliding_variable(0.01)), g.lambda * std::cosh(g.delta2 * 0.01));
}

TEST(TerminalSlidingMode, RejectsAContractionOutsideTheUnitInterval) {
  TerminalSlidingModeGains g;
  g.q = 2000.0;  // 1 - qT = -1 at T = 1 ms
  EXPECT_THROW(TerminalSlidingMode(g, 1e-3), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::control

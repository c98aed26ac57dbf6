// The fifth-order Taylor step of the friction axes, against a closed form (no friction), against
// RK4 at 1 us steps (a second method), for its order of convergence, and for its refusal where
// its series would not hold.
#include "plant/coulomb_taylor_step.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "closed_form.hpp"
#include "plant/rk4_integrator.hpp"
#include "plant/smooth_sign.hpp"

namespace netmc::plant {
namespace {

// Paper 001's Y axis as the catalog calibrates it (plant/models/seed001.cpp): a2 = -10 1/s,
// friction 85 mm/s^2 smoothed over 1 mm/s; the forcing drives the velocity through zero.
CoulombAxisCoefficients seed001_y(double w) { return {0.0, -10.0, w, 0.085, 1.0 / 1e-3}; }

struct State {
  double x = 0.0;
  double v = 0.0;
};

State taylor(State s, const CoulombAxisCoefficients& k, double h, int steps) {
  for (int i = 0; i < steps; ++i) {
    if (!coulomb_taylor_step(s.x, s.v, h, k)) ADD_FAILURE() << "step " << i << " refused";
  }
  return s;
}

State rk4(State s, const CoulombAxisCoefficients& k, double duration, long long steps) {
  rk4_second_order(s.x, s.v, 0.0, duration, steps, [&](double, double x, double v) {
    return k.a1 * x + k.a2 * v + k.w - k.c * smooth_sign(v * k.inv_scale);
  });
  return s;
}

TEST(CoulombTaylorStep, WithoutFrictionMatchesTheClosedForm) {
  CoulombAxisCoefficients k = seed001_y(0.4);
  k.c = 0.0;
  k.inv_scale = 1.0;  // no friction to smooth: every step is within reach
  const State s = taylor({0.01, -0.02}, k, 1e-3, 200);
  const auto truth = test::damped_axis_step(k.a2, k.w, 0.01, -0.02, 0.2);
  EXPECT_LT(test::relative_error(s.x, truth.x), 1e-12);
  EXPECT_LT(test::relative_error(s.v, truth.v), 1e-12);
}

TEST(CoulombTaylorStep, ThroughAVelocityReversalMatchesFineRk4BetterThanRk4AtTheSameStep) {
  // From -1 mm/s, a forcing of 0.02 m/s^2 turns the axis round within the friction's smooth
  // band (|v| < 1 mm/s), where the friction changes fastest.
  const auto k = seed001_y(0.02);
  const State start{0.0, -1e-3};
  const double duration = 0.2;
  const State truth = rk4(start, k, duration, 200'000);  // 1 us steps
  ASSERT_GT(truth.v, 1e-4);                               // it did reverse
  const State fast = taylor(start, k, 1e-3, 200);
  const State reference_method = rk4(start, k, duration, 200);
  const double taylor_error = std::abs(fast.x - truth.x) + duration * std::abs(fast.v - truth.v);
  const double rk4_error = std::abs(reference_method.x - truth.x) + duration * std::abs(reference_method.v - truth.v);
  EXPECT_LT(taylor_error, 1e-12);
  EXPECT_LT(taylor_error, rk4_error);
}

TEST(CoulombTaylorStep, ErrorShrinksLikeHToTheFifth) {
  const auto k = seed001_y(0.02);
  const State start{0.0, -1e-3};
  const State truth = rk4(start, k, 0.01, 100'000);
  double previous = 0.0;
  for (const int steps : {10, 20, 40}) {
    const State s = taylor(start, k, 0.01 / steps, steps);
    const double error = std::abs(s.v - truth.v);
    if (previous > 0.0) {
      EXPECT_GT(previous / error, 20.0) << steps << " steps";  // 2^5 = 32
      EXPECT_LT(previous / error, 50.0) << steps << " steps";
    }
    previous = error;
  }
  EXPECT_GT(previous, 1e-15);  // above round-off, so the ratios mean something
}

TEST(CoulombTaylorStep, RefusesAStepOverWhichTheFrictionArgumentMovesTooFarAndLeavesTheState) {
  const auto k = seed001_y(20.0);  // 20 m/s^2: 20 units of x'/s in a millisecond
  double x = 0.001, v = 0.0;
  EXPECT_FALSE(coulomb_taylor_step(x, v, 1e-3, k));
  EXPECT_EQ(x, 0.001);
  EXPECT_EQ(v, 0.0);
  // The same acceleration over a step short enough is taken.
  EXPECT_TRUE(coulomb_taylor_step(x, v, 0.5 * kCoulombTaylorReach * 1e-3 / 20.0, k));
  EXPECT_GT(v, 0.0);
  // Non-finite states are refused too.
  double bad_v = std::nan("");
  EXPECT_FALSE(coulomb_taylor_step(x, bad_v, 1e-3, k));
}

}  // namespace
}  // namespace netmc::plant

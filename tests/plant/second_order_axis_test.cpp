#include "plant/second_order_axis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "closed_form.hpp"

namespace netmc::plant {
namespace {

using test::damped_axis_sine;
using test::damped_axis_step;
using test::relative_error;

SecondOrderAxisParameters linear_x() {
  SecondOrderAxisParameters p;
  p.a1 = 0.0;
  p.a2 = -20.0;
  p.b = 20.0;
  return p;
}

TEST(SecondOrderAxis, ExactStepResponseMatchesClosedForm) {
  const SecondOrderAxisParameters p = linear_x();
  SecondOrderAxis axis(p);
  const double x0 = 0.01, v0 = -0.02, u = 0.7, h = 5e-3;
  axis.reset(x0, v0);
  for (int k = 1; k <= 200; ++k) {
    axis.advance(h, u);
    const double t = k * h;
    const auto truth = damped_axis_step(p.a2, p.b * u, x0, v0, t);
    ASSERT_LT(relative_error(axis.position(), truth.x), 1e-12) << "t=" << t;
    ASSERT_LT(relative_error(axis.velocity(), truth.v), 1e-12) << "t=" << t;
    ASSERT_NEAR(axis.time(), t, 1e-14);
  }
}

// Forced onto RK4 by a Coulomb level of 1e-300 m/s^2 (no effect on the state at double precision).
double rk4_error(double max_substep, bool position) {
  SecondOrderAxisParameters p = linear_x();
  p.coulomb_acceleration = 1e-300;
  p.max_substep_s = max_substep;
  SecondOrderAxis axis(p);
  axis.reset(0.0, 0.0);
  axis.advance(0.5, 1.0);
  const auto truth = damped_axis_step(p.a2, p.b, 0.0, 0.0, 0.5);
  return position ? std::abs(axis.position() - truth.x) : std::abs(axis.velocity() - truth.v);
}

TEST(SecondOrderAxis, Rk4ErrorShrinksLikeH4) {
  for (bool position : {true, false}) {
    double previous = rk4_error(1e-2, position);
    EXPECT_GT(previous, 1e-11);  // well above round-off, so the ratios mean something
    for (double h : {5e-3, 2.5e-3, 1.25e-3}) {
      const double e = rk4_error(h, position);
      const double ratio = previous / e;
      EXPECT_GT(ratio, 12.0) << "h=" << h << " position=" << position;
      EXPECT_LT(ratio, 20.0) << "h=" << h << " position=" << position;
      previous = e;
    }
  }
}

TEST(SecondOrderAxis, Rk4WithSineDisturbanceMatchesClosedForm) {
  SecondOrderAxisParameters p = linear_x();
  const double amp = 0.3, freq = 3.0, phase = 0.4, u = 0.5;
  p.disturbance.sine_amplitude = amp;
  p.disturbance.sine_frequency_hz = freq;
  p.disturbance.sine_phase_rad = phase;
  SecondOrderAxis axis(p);
  axis.reset(0.0, 0.0);
  for (int k = 1; k <= 200; ++k) {
    axis.advance(5e-3, u);
    const double t = k * 5e-3;
    // Linear: response to b u plus response to the sine.
    const auto step = damped_axis_step(p.a2, p.b * u, 0.0, 0.0, t);
    const auto sine = damped_axis_sine(p.a2, amp, 2.0 * std::numbers::pi * freq, phase, t);
    ASSERT_LT(relative_error(axis.position(), step.x + sine.x), 1e-10) << "t=" << t;
    ASSERT_LT(relative_error(axis.velocity(), step.v + sine.v), 1e-10) << "t=" << t;
  }
}

TEST(SecondOrderAxis, ConstantDisturbanceShiftsSteadyVelocity) {
  SecondOrderAxisParameters p = linear_x();
  SecondOrderAxis plain(p);
  p.disturbance.constant = 0.4;
  SecondOrderAxis disturbed(p);
  plain.reset(0.0, 0.0);
  disturbed.reset(0.0, 0.0);
  for (int k = 0; k < 600; ++k) {  // 3 s = 60 time constants
    plain.advance(5e-3, 1.0);
    disturbed.advance(5e-3, 1.0);
  }
  EXPECT_NEAR(plain.velocity(), p.b * 1.0 / -p.a2, 1e-12);
  EXPECT_NEAR(disturbed.velocity() - plain.velocity(), 0.4 / -p.a2, 1e-12);
}

TEST(SecondOrderAxis, SplitAdvanceEqualsSingleAdvance) {
  for (double a1 : {0.0, -400.0, 30.0}) {
    SecondOrderAxisParameters p = linear_x();
    p.a1 = a1;
    for (double tau : {1e-5, 3e-4, 2.5e-3, 4.9e-3}) {
      SecondOrderAxis whole(p);
      SecondOrderAxis split(p);
      whole.reset(0.003, 0.05);
      split.reset(0.003, 0.05);
      for (int k = 0; k < 20; ++k) {
        const double u = std::sin(0.7 * k);
        whole.advance(5e-3, u);
        split.advance(tau, u);
        split.advance(5e-3 - tau, u);
      }
      EXPECT_LT(relative_error(split.position(), whole.position()), 1e-12) << a1 << " " << tau;
      EXPECT_LT(relative_error(split.velocity(), whole.velocity()), 1e-12) << a1 << " " << tau;
      EXPECT_NEAR(split.time(), whole.time(), 1e-15);
    }
  }
}

TEST(SecondOrderAxis, SplitAdvanceOnRk4PathAgreesClosely) {
  SecondOrderAxisParameters p = linear_x();
  p.coulomb_acceleration = 0.05;
  SecondOrderAxis whole(p);
  SecondOrderAxis split(p);
  whole.reset(0.0, 0.0);
  split.reset(0.0, 0.0);
  for (int k = 0; k < 50; ++k) {
    const double u = 0.01 * std::sin(0.3 * k);
    whole.advance(5e-3, u);
    split.advance(7e-4, u);
    split.advance(5e-3 - 7e-4, u);
  }
  EXPECT_NEAR(split.position(), whole.position(), 1e-12);
  EXPECT_NEAR(split.velocity(), whole.velocity(), 1e-10);
}

// Paper 001, eq. 4: with u(k-1) acting for tau and u(k) for h - tau, the velocity update is
// exact when a1 = 0 (eq. 4's position update is forward Euler, so only x2 is compared).
TEST(SecondOrderAxis, TwoSegmentExactMatchesPaper001Eq4Velocity) {
  const SecondOrderAxisParameters p = linear_x();
  SecondOrderAxis axis(p);
  axis.reset(0.06, 0.0);
  const double h = 5e-3;
  double u_prev = 0.0;
  for (int k = 0; k < 100; ++k) {
    const double tau = 3e-4 + 5e-4 * std::abs(std::sin(1.3 * k));  // 0.3 .. 0.8 ms
    const double u = 0.2 * std::cos(0.1 * k) + 0.05;
    const double x2 = axis.velocity();
    const double e_h = std::exp(p.a2 * h);
    const double e_rest = std::exp(p.a2 * (h - tau));
    const double eq4 =
        e_h * x2 + p.b / p.a2 * (e_rest - 1.0) * u + p.b / p.a2 * (e_h - e_rest) * u_prev;
    axis.advance(tau, u_prev);
    axis.advance(h - tau, u);
    ASSERT_NEAR(axis.velocity(), eq4, 1e-9) << "k=" << k;
    u_prev = u;
  }
}

TEST(SecondOrderAxis, ExactPathAgreesWithFineRk4ForSpringAxis) {
  SecondOrderAxisParameters p = linear_x();
  p.a1 = -400.0;
  p.a2 = -4.0;
  SecondOrderAxis exact(p);
  p.coulomb_acceleration = 1e-300;
  p.max_substep_s = 1e-5;
  SecondOrderAxis rk4(p);
  exact.reset(0.01, 0.0);
  rk4.reset(0.01, 0.0);
  for (int k = 0; k < 200; ++k) {
    exact.advance(5e-3, 0.1);
    rk4.advance(5e-3, 0.1);
  }
  EXPECT_NEAR(exact.position(), rk4.position(), 1e-12);
  EXPECT_NEAR(exact.velocity(), rk4.velocity(), 1e-10);
}

// A step disturbance in the acceleration equals an input step of d/b at the same instant.
TEST(SecondOrderAxis, StepDisturbanceSwitchesInsideAnInterval) {
  SecondOrderAxisParameters p = linear_x();
  SecondOrderAxis reference(p);
  p.disturbance.step_amplitude = 0.4;
  p.disturbance.step_time_s = 0.0123;
  SecondOrderAxis disturbed(p);
  reference.reset(0.0, 0.0);
  disturbed.reset(0.0, 0.0);
  for (int k = 0; k < 10; ++k) disturbed.advance(5e-3, 0.5);
  reference.advance(0.0123, 0.5);
  reference.advance(0.05 - 0.0123, 0.5 + 0.4 / p.b);
  EXPECT_LT(relative_error(disturbed.position(), reference.position()), 1e-12);
  EXPECT_LT(relative_error(disturbed.velocity(), reference.velocity()), 1e-12);
}

TEST(SecondOrderAxis, CoulombFrictionSlowsSteadyVelocity) {
  SecondOrderAxisParameters p = linear_x();
  p.coulomb_acceleration = 0.05;
  SecondOrderAxis axis(p);
  axis.reset(0.0, 0.0);
  for (int k = 0; k < 400; ++k) axis.advance(5e-3, 0.5);
  // a2 v + b u - c = 0 once tanh has saturated.
  EXPECT_NEAR(axis.velocity(), (p.b * 0.5 - 0.05) / -p.a2, 1e-9);
  // Below the Coulomb level (b u < c) only a creep of the order of the tanh scale remains.
  SecondOrderAxis stuck(p);
  stuck.reset(0.0, 0.0);
  for (int k = 0; k < 200; ++k) stuck.advance(5e-3, 0.5 * 0.05 / p.b);
  EXPECT_LT(std::abs(stuck.velocity()), p.coulomb_velocity_scale);
  EXPECT_GT(stuck.velocity(), 0.0);
}

TEST(SecondOrderAxis, ZeroDurationIsANoOpAndResetRestartsTime) {
  SecondOrderAxis axis(linear_x());
  axis.reset(0.1, 0.2);
  axis.advance(0.0, 5.0);
  EXPECT_EQ(axis.position(), 0.1);
  EXPECT_EQ(axis.velocity(), 0.2);
  EXPECT_EQ(axis.time(), 0.0);
  axis.advance(0.01, 1.0);
  EXPECT_DOUBLE_EQ(axis.time(), 0.01);
  axis.reset(-0.3, 0.0);
  EXPECT_EQ(axis.time(), 0.0);
  EXPECT_EQ(axis.position(), -0.3);
  EXPECT_EQ(axis.velocity(), 0.0);
}

TEST(SecondOrderAxis, RejectsBadParametersAndArguments) {
  auto expect_throw_naming = [](SecondOrderAxisParameters p, const std::string& name) {
    try {
      SecondOrderAxis axis(p);
      ADD_FAILURE() << "no throw for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  SecondOrderAxisParameters p;
  p.a2 = std::nan("");
  expect_throw_naming(p, "a2");
  p = {};
  p.max_substep_s = 0.0;
  expect_throw_naming(p, "max_substep_s");
  p = {};
  p.coulomb_velocity_scale = -1.0;
  expect_throw_naming(p, "coulomb_velocity_scale");
  p = {};
  p.coulomb_acceleration = -0.1;
  expect_throw_naming(p, "coulomb_acceleration");
  p = {};
  p.disturbance.sine_amplitude = INFINITY;
  expect_throw_naming(p, "disturbance.sine_amplitude");

  SecondOrderAxis axis(linear_x());
  EXPECT_THROW(axis.advance(-1e-3, 0.0), std::invalid_argument);
  EXPECT_THROW(axis.advance(std::nan(""), 0.0), std::invalid_argument);
  EXPECT_THROW(axis.advance(1e-3, std::nan("")), std::invalid_argument);
  EXPECT_THROW(axis.reset(std::nan(""), 0.0), std::invalid_argument);
  EXPECT_EQ(axis.position(), 0.0);  // a rejected call leaves the state alone
}

TEST(SecondOrderAxis, CloneCopiesStateAndEvolvesIndependently) {
  SecondOrderAxisParameters p = linear_x();
  p.coulomb_acceleration = 0.05;
  p.disturbance.sine_amplitude = 0.1;
  p.disturbance.sine_frequency_hz = 2.0;
  SecondOrderAxis axis(p);
  axis.reset(0.01, 0.0);
  for (int k = 0; k < 10; ++k) axis.advance(5e-3, 0.3);
  auto copy = axis.clone();
  EXPECT_EQ(copy->position(), axis.position());
  EXPECT_EQ(copy->velocity(), axis.velocity());
  EXPECT_EQ(copy->time(), axis.time());
  EXPECT_EQ(copy->describe(), axis.describe());
  copy->advance(5e-3, -1.0);
  EXPECT_NE(copy->position(), axis.position());
  axis.advance(5e-3, -1.0);
  EXPECT_EQ(copy->position(), axis.position());
  EXPECT_EQ(copy->velocity(), axis.velocity());
}

TEST(SecondOrderAxis, DescribeNamesTheKeyParameters) {
  SecondOrderAxisParameters p = linear_x();
  p.coulomb_acceleration = 0.05;
  const std::string text = SecondOrderAxis(p).describe();
  EXPECT_NE(text.find("a2=-20"), std::string::npos) << text;
  EXPECT_NE(text.find("coulomb=0.05"), std::string::npos) << text;
  EXPECT_EQ(text.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace netmc::plant

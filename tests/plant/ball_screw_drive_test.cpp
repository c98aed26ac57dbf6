#include "plant/ball_screw_drive.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "closed_form.hpp"

namespace netmc::plant {
namespace {

using test::damped_axis_sine;
using test::damped_axis_step;
using test::relative_error;

TEST(BallScrewDrive, NominalCoefficientsMatchPaper002) {
  const BallScrewDrive drive{BallScrewParameters{}};
  // Derived from paper 002, eq. 1: B/J = 318.75 1/s, Ka Kt rg / J = 18000 mm/(V s^2) = 18 m/(V s^2).
  EXPECT_NEAR(drive.damping_rate(), 318.75, 1e-12);
  EXPECT_NEAR(drive.input_gain(), 18.0, 1e-12);
}

TEST(BallScrewDrive, SteadySpeedIs56_47MillimetresPerSecondPerVolt) {
  BallScrewDrive drive{BallScrewParameters{}};
  drive.reset(0.0, 0.0);
  for (int k = 0; k < 200; ++k) drive.advance(1e-3, 1.0);  // 64 time constants of 3.1 ms
  EXPECT_NEAR(drive.velocity() * 1e3, 56.47, 0.005);
  EXPECT_NEAR(drive.velocity(), 18.0 / 318.75, 1e-12);
  drive.reset(0.0, 0.0);
  for (int k = 0; k < 200; ++k) drive.advance(1e-3, -2.5);
  EXPECT_NEAR(drive.velocity(), -2.5 * 18.0 / 318.75, 1e-12);
}

TEST(BallScrewDrive, ExactStepResponseMatchesClosedForm) {
  BallScrewDrive drive{BallScrewParameters{}};
  drive.reset(0.02, 0.01);
  for (int k = 1; k <= 100; ++k) {
    drive.advance(1e-3, 0.8);
    const auto truth = damped_axis_step(-318.75, 18.0 * 0.8, 0.02, 0.01, k * 1e-3);
    ASSERT_LT(relative_error(drive.position(), truth.x), 1e-12) << k;
    ASSERT_LT(relative_error(drive.velocity(), truth.v), 1e-12) << k;
  }
}

// Paper 002, eq. 2 (forward differences, T = 1 ms):
//   y(k+2) = (2 - BT/J) y(k+1) + (BT/J - 1) y(k) + T^2 Ka Kt rg / J (u(k) + d(k)).
// It is a coarse model (BT/J = 0.32), but it has the same steady speed and the same asymptote
// v (t - J/B), so it must follow the exact plant closely.
TEST(BallScrewDrive, ForwardDifferenceRecursionApproximatesThePlant) {
  const double T = 1e-3, a = 318.75 * T, g = 18.0 * T * T, u = 1.0;
  BallScrewDrive drive{BallScrewParameters{}};
  drive.reset(0.0, 0.0);
  std::vector<double> rec = {0.0, 0.0};  // y(0) = 0, y(1) = y(0) + T y'(0) = 0
  std::vector<double> exact = {0.0};
  for (int k = 0; k < 300; ++k) {
    drive.advance(T, u);
    exact.push_back(drive.position());
    rec.push_back((2.0 - a) * rec[rec.size() - 1] + (a - 1.0) * rec[rec.size() - 2] + g * u);
  }
  const double v_ss = 18.0 / 318.75;
  for (std::size_t k = 0; k < exact.size(); ++k) {
    // Never more than about one sample of travel apart.
    ASSERT_LT(std::abs(rec[k] - exact[k]), v_ss * T) << k;
  }
  // After the transient the two agree to a small fraction of the distance travelled.
  EXPECT_LT(std::abs(rec[300] - exact[300]), 1e-6 * exact[300]);
  EXPECT_NEAR((rec[300] - rec[299]) / T, v_ss, 1e-9);
}

TEST(BallScrewDrive, DisturbanceAddsToTheInputVoltage) {
  BallScrewParameters p;
  p.disturbance.constant = 0.5;
  BallScrewDrive drive(p);
  drive.reset(0.0, 0.0);
  for (int k = 0; k < 200; ++k) drive.advance(1e-3, 1.0);
  EXPECT_NEAR(drive.velocity(), 1.5 * 18.0 / 318.75, 1e-12);
}

TEST(BallScrewDrive, SineDisturbanceUsesRk4AndMatchesClosedForm) {
  BallScrewParameters p;
  const double amp = 0.2, freq = 5.0, phase = -0.3;
  p.disturbance.sine_amplitude = amp;
  p.disturbance.sine_frequency_hz = freq;
  p.disturbance.sine_phase_rad = phase;
  BallScrewDrive drive(p);
  drive.reset(0.0, 0.0);
  for (int k = 1; k <= 300; ++k) {
    drive.advance(1e-3, 0.3);
    const double t = k * 1e-3;
    const auto step = damped_axis_step(-318.75, 18.0 * 0.3, 0.0, 0.0, t);
    const auto sine =
        damped_axis_sine(-318.75, 18.0 * amp, 2.0 * std::numbers::pi * freq, phase, t);
    // RK4 at the default 0.1 ms sub-step (|lambda h| = 0.03): worst right after the start.
    ASSERT_LT(relative_error(drive.position(), step.x + sine.x), 1e-7) << t;
    ASSERT_LT(relative_error(drive.velocity(), step.v + sine.v), 1e-8) << t;
  }
}

TEST(BallScrewDrive, SplitAdvanceEqualsSingleAdvance) {
  BallScrewDrive whole{BallScrewParameters{}};
  BallScrewDrive split{BallScrewParameters{}};
  whole.reset(0.0, 0.0);
  split.reset(0.0, 0.0);
  for (int k = 0; k < 50; ++k) {
    const double u = std::cos(0.2 * k);
    whole.advance(1e-3, u);
    split.advance(3.3e-4, u);
    split.advance(1e-3 - 3.3e-4, u);
  }
  EXPECT_LT(relative_error(split.position(), whole.position()), 1e-12);
  EXPECT_LT(relative_error(split.velocity(), whole.velocity()), 1e-12);
}

TEST(BallScrewDrive, RejectsBadParameters) {
  auto check = [](BallScrewParameters p, const std::string& name) {
    try {
      BallScrewDrive drive(p);
      ADD_FAILURE() << "no throw for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  BallScrewParameters p;
  p.inertia = 0.0;
  check(p, "inertia");
  p = {};
  p.damping = -0.1;
  check(p, "damping");
  p = {};
  p.lead_m_per_rad = std::nan("");
  check(p, "lead_m_per_rad");
  p = {};
  p.max_substep_s = -1e-4;
  check(p, "max_substep_s");
  BallScrewDrive drive{BallScrewParameters{}};
  EXPECT_THROW(drive.advance(-1.0, 0.0), std::invalid_argument);
}

TEST(BallScrewDrive, CloneAndDescribe) {
  BallScrewDrive drive{BallScrewParameters{}};
  drive.reset(0.0, 0.0);
  drive.advance(2e-3, 1.0);
  auto copy = drive.clone();
  copy->advance(1e-3, 0.5);
  drive.advance(1e-3, 0.5);
  EXPECT_EQ(copy->position(), drive.position());
  EXPECT_EQ(copy->velocity(), drive.velocity());
  EXPECT_EQ(copy->time(), drive.time());
  EXPECT_NE(drive.describe().find("J=0.0008"), std::string::npos) << drive.describe();
}

}  // namespace
}  // namespace netmc::plant

namespace netmc::plant {
namespace {

// A step that switches off is the difference of two steps that stay on (the drive is linear):
// independent of how the integrator splits the interval at the switches.
TEST(BallScrewDrive, StepOnAndOffIsTheDifferenceOfTwoSteps) {
  auto run = [](double amplitude, double on, double off) {
    BallScrewParameters p;
    p.disturbance.step_amplitude = amplitude;
    p.disturbance.step_time_s = on;
    p.disturbance.step_off_s = off;
    BallScrewDrive drive(p);
    drive.reset(0.0, 0.0);
    std::vector<double> positions;
    for (int k = 0; k < 800; ++k) {
      drive.advance(0.01, 0.3);
      positions.push_back(drive.position());
    }
    return positions;
  };
  const double infinity = std::numeric_limits<double>::infinity();
  const auto window = run(0.8, 2.2, 5.2);
  const auto from_on = run(0.8, 2.2, infinity);
  const auto from_off = run(0.8, 5.2, infinity);
  const auto without = run(0.0, 0.0, infinity);
  double largest_effect = 0.0;
  for (std::size_t k = 0; k < window.size(); ++k) {
    EXPECT_NEAR(window[k], without[k] + (from_on[k] - without[k]) - (from_off[k] - without[k]), 1e-12) << k;
    largest_effect = std::max(largest_effect, std::abs(window[k] - without[k]));
  }
  EXPECT_GT(largest_effect, 0.1);  // the step moved the axis by more than 10 cm: the test has teeth
  EXPECT_EQ(window[210], without[210]);  // before the step (t = 2.11 s) nothing differs
}

}  // namespace
}  // namespace netmc::plant

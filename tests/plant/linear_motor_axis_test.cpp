#include "plant/linear_motor_axis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "closed_form.hpp"

namespace netmc::plant {
namespace {

using test::damped_axis_step;
using test::relative_error;

LinearMotorParameters thesis_x() {  // paper 000 appendix A.8 nominal, no cogging
  LinearMotorParameters p;
  p.mass = 0.12;
  p.damping = 0.3;
  p.coulomb = 0.1;
  return p;
}

// Mean period from upward zero crossings of samples taken every dt (linear interpolation).
double mean_period(const std::vector<double>& y, double dt) {
  std::vector<double> crossings;
  for (std::size_t k = 1; k < y.size(); ++k) {
    if (y[k - 1] < 0.0 && y[k] >= 0.0) {
      crossings.push_back((static_cast<double>(k) - y[k] / (y[k] - y[k - 1])) * dt);
    }
  }
  if (crossings.size() < 2) return 0.0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

TEST(LinearMotorAxis, SmallForceBelowCoulombLevelBarelyMoves) {
  LinearMotorAxis axis(thesis_x());
  for (double u : {0.05, -0.08}) {
    axis.reset(0.0, 0.0);
    for (int k = 0; k < 5000; ++k) axis.advance(2e-4, u);  // 1 s at the thesis' Ts
    // Without friction the same force would reach u/B = 0.17 m/s and travel ~0.1 m.
    EXPECT_LT(std::abs(axis.velocity()), 2.0 * 1e-4) << u;  // tanh creep, ~ the smoothing speed
    EXPECT_LT(std::abs(axis.position()), 2e-4) << u;
    EXPECT_GT(axis.velocity() * u, 0.0);  // the creep follows the force
  }
}

TEST(LinearMotorAxis, LargeForceReachesViscousSteadyVelocity) {
  LinearMotorAxis x_axis(thesis_x());
  x_axis.reset(0.0, 0.0);
  for (int k = 0; k < 8000; ++k) x_axis.advance(1e-3, 0.5);  // 20 time constants M/B
  EXPECT_NEAR(x_axis.velocity(), (0.5 - 0.1) / 0.3, 1e-7);

  LinearMotorParameters y = thesis_x();
  y.mass = 0.55;
  y.damping = 0.4;
  y.coulomb = 0.15;
  LinearMotorAxis y_axis(y);
  y_axis.reset(0.0, 0.0);
  for (int k = 0; k < 30000; ++k) y_axis.advance(1e-3, -0.5);
  EXPECT_NEAR(y_axis.velocity(), (-0.5 + 0.15) / 0.4, 1e-7);
}

TEST(LinearMotorAxis, StribeckPeakHoldsAForceThatCoulombAloneWouldNot) {
  LinearMotorParameters p = thesis_x();
  p.stribeck_extra = 0.1;
  p.stribeck_velocity = 0.01;
  const LinearMotorAxis probe(p);
  // Friction law, eq. A.3 with xi = 2 and a tanh sign.
  for (double v : {1e-3, 0.02, -0.005}) {
    const double expected = (0.1 + 0.1 * std::exp(-(v / 0.01) * (v / 0.01))) * std::tanh(v / 1e-4);
    EXPECT_NEAR(probe.friction_force(v), expected, 1e-15);
  }
  LinearMotorAxis with(p);
  LinearMotorAxis without(thesis_x());
  with.reset(0.0, 0.0);
  without.reset(0.0, 0.0);
  for (int k = 0; k < 1000; ++k) {
    with.advance(1e-3, 0.15);  // between A = 0.1 and A + extra = 0.2
    without.advance(1e-3, 0.15);
  }
  EXPECT_LT(std::abs(with.velocity()), 2e-4);
  EXPECT_GT(without.velocity(), 0.1);
}

TEST(LinearMotorAxis, CoggingFollowsPaper000Eq4_2) {
  LinearMotorParameters p = thesis_x();
  p.cogging_pitch_m = 0.05;
  p.cogging = {{0.05, 0.03, 1}, {0.02, -0.01, 2}, {0.01, 0.01, 3}};
  const LinearMotorAxis axis(p);
  for (double y : {0.0, 0.0037, -0.021, 0.3}) {
    double expected = 0.0;
    for (const auto& h : p.cogging) {
      const double phase = 2.0 * h.order * std::numbers::pi * y / 0.05;
      expected += h.sine * std::sin(phase) + h.cosine * std::cos(phase);
    }
    EXPECT_NEAR(axis.cogging_force(y), expected, 1e-15) << y;
    EXPECT_NEAR(axis.cogging_force(y + 0.05), expected, 1e-14) << "periodic in the pitch";
  }
}

// Cogging alone (no friction, no damping): M y'' = -S sin(2 pi i y / P) is a stiffness
// 2 pi i S / P around y = 0, so small oscillations have w = sqrt(2 pi i S / (P M)).
TEST(LinearMotorAxis, CoggingStiffnessSetsSmallOscillationFrequency) {
  for (int order : {1, 2}) {
    LinearMotorParameters p;
    p.mass = 0.12;
    p.damping = 0.0;
    p.coulomb = 0.0;
    p.cogging_pitch_m = 0.05;
    p.cogging = {{0.05, 0.0, order}};
    LinearMotorAxis axis(p);
    axis.reset(1e-5, 0.0);
    const double dt = 1e-3;
    std::vector<double> y;
    for (int k = 0; k < 6000; ++k) {
      axis.advance(dt, 0.0);
      y.push_back(axis.position());
    }
    const double w = std::sqrt(2.0 * std::numbers::pi * order * 0.05 / (0.05 * 0.12));
    EXPECT_LT(relative_error(mean_period(y, dt), 2.0 * std::numbers::pi / w), 1e-4) << order;
  }
}

TEST(LinearMotorAxis, CosineCoggingPushesFromRest) {
  LinearMotorParameters p = thesis_x();
  p.coulomb = 0.0;
  p.cogging = {{0.0, 0.03, 1}};
  LinearMotorAxis axis(p);
  axis.reset(0.0, 0.0);
  axis.advance(1e-4, 0.0);
  // y'' = -C/M at y = 0 (velocity too small for damping to matter yet).
  EXPECT_LT(relative_error(axis.velocity(), -0.03 / 0.12 * 1e-4), 1e-3);
}

TEST(LinearMotorAxis, FrictionlessAxisIsExactAgainstClosedForm) {
  LinearMotorParameters p = thesis_x();
  p.coulomb = 0.0;
  LinearMotorAxis axis(p);
  axis.reset(0.0, 0.1);
  for (int k = 1; k <= 100; ++k) {
    axis.advance(2e-4, 0.7);
    const auto truth = damped_axis_step(-0.3 / 0.12, 0.7 / 0.12, 0.0, 0.1, k * 2e-4);
    ASSERT_LT(relative_error(axis.position(), truth.x), 1e-12) << k;
    ASSERT_LT(relative_error(axis.velocity(), truth.v), 1e-12) << k;
  }
}

TEST(LinearMotorAxis, StepDisturbanceActsLikeTheThesisSet3InputStep) {
  // Set3 (paper 000 ch. 3): +0.8 V on the input from t = 2.2 s.
  LinearMotorParameters p = thesis_x();
  p.coulomb = 0.0;
  p.disturbance.step_amplitude = 0.8;
  p.disturbance.step_time_s = 0.0101;
  LinearMotorAxis disturbed(p);
  p.disturbance = {};
  LinearMotorAxis reference(p);
  disturbed.reset(0.0, 0.0);
  reference.reset(0.0, 0.0);
  for (int k = 0; k < 100; ++k) disturbed.advance(2e-4, 0.1);
  reference.advance(0.0101, 0.1);
  reference.advance(0.02 - 0.0101, 0.9);
  EXPECT_LT(relative_error(disturbed.position(), reference.position()), 1e-12);
  EXPECT_LT(relative_error(disturbed.velocity(), reference.velocity()), 1e-12);
}

TEST(LinearMotorAxis, RejectsBadParameters) {
  auto check = [](LinearMotorParameters p, const std::string& name) {
    try {
      LinearMotorAxis axis(p);
      ADD_FAILURE() << "no throw for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  LinearMotorParameters p;
  p.mass = std::nan("");
  check(p, "mass");
  p = {};
  p.mass = -0.1;
  check(p, "mass");
  p = {};
  p.cogging_pitch_m = 0.0;
  check(p, "cogging_pitch_m");
  p = {};
  p.cogging = {{0.1, 0.0, 0}};
  check(p, "cogging[0].order");
  p = {};
  p.cogging = {{0.1, 0.0, 1}, {std::nan(""), 0.0, 2}};
  check(p, "cogging[1].sine");
  p = {};
  p.friction_smoothing_velocity = 0.0;
  check(p, "friction_smoothing_velocity");
}

TEST(LinearMotorAxis, CloneAndDescribe) {
  LinearMotorParameters p = thesis_x();
  p.cogging = {{0.05, 0.03, 1}};
  LinearMotorAxis axis(p);
  axis.reset(0.0, 0.0);
  axis.advance(1e-3, 0.4);
  auto copy = axis.clone();
  EXPECT_EQ(copy->position(), axis.position());
  copy->advance(1e-3, 0.4);
  axis.advance(1e-3, 0.4);
  EXPECT_EQ(copy->position(), axis.position());
  EXPECT_EQ(copy->velocity(), axis.velocity());
  const std::string text = axis.describe();
  EXPECT_NE(text.find("M=0.12"), std::string::npos) << text;
  EXPECT_NE(text.find("P=0.05"), std::string::npos) << text;
}

}  // namespace
}  // namespace netmc::plant

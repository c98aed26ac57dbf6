#include "plant/resonant_stage_axis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "closed_form.hpp"

namespace netmc::plant {
namespace {

using test::mode_step;
using test::relative_error;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

ResonantStageParameters table1_x() {  // paper 004, Table 1
  ResonantStageParameters p;
  p.mass = 24.0;
  p.modes = {{0.013, 0.040, 150.0}, {0.0023, 0.018, 292.0}, {0.0018, 0.027, 510.0}};
  return p;
}

double truth_position(const ResonantStageParameters& p, double force, double t) {
  double y = force * t * t / (2.0 * p.mass);
  for (const auto& m : p.modes) {
    y += mode_step(m.gain, m.damping_ratio, kTwoPi * m.frequency_hz, force, t).x;
  }
  return y;
}

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

TEST(ResonantStageAxis, ConstantForceResponseMatchesClosedForm) {
  const ResonantStageParameters p = table1_x();
  ResonantStageAxis axis(p);
  axis.reset(0.0, 0.0);
  const double force = 10.0;
  for (int k = 1; k <= 1000; ++k) {
    axis.advance(1e-3, force);
    const double t = k * 1e-3;
    ASSERT_LT(relative_error(axis.position(), truth_position(p, force, t)), 1e-11) << t;
  }
}

// DC behaviour: the rigid body 1/(m s^2) dominates and each mode adds its static deflection
// K_i F / (2 pi f_i)^2 once its transient has died out.
TEST(ResonantStageAxis, DcBehaviourIsRigidBodyPlusStaticModalDeflection) {
  for (const ResonantStageParameters& p :
       {table1_x(), ResonantStageParameters{
                        30.0, {{0.018, 0.0432, 182.0}, {0.0021, 0.0531, 302.0}}, {}, 1e-5}}) {
    ResonantStageAxis axis(p);
    axis.reset(0.0, 0.0);
    const double force = 5.0, t = 1.0;
    for (int k = 0; k < 200; ++k) axis.advance(t / 200.0, force);
    double static_modes = 0.0;
    for (const auto& m : p.modes)
      static_modes += m.gain * force / std::pow(kTwoPi * m.frequency_hz, 2);
    const double rigid = force * t * t / (2.0 * p.mass);
    EXPECT_NEAR(axis.position(), rigid + static_modes, 1e-6 * static_modes);
    EXPECT_NEAR(axis.velocity(), force * t / p.mass, 1e-9);
    EXPECT_GT(static_modes, 1e-9);  // the modal part is really there (not lost in round-off)
  }
}

// A kicked mode rings at its damped natural frequency f sqrt(1 - x^2), on the exact path and on
// the RK4 path (forced by a 1e-300 N sine, far below double precision of the response).
TEST(ResonantStageAxis, ModeRingsAtItsDampedFrequency) {
  for (bool rk4 : {false, true}) {
    ResonantStageParameters p;
    p.mass = 1e9;  // rigid body practically fixed: the output is the mode alone
    p.modes = {{0.013, 0.040, 150.0}};
    if (rk4) {
      p.disturbance.sine_amplitude = 1e-300;
      p.disturbance.sine_frequency_hz = 1.0;
    }
    ResonantStageAxis axis(p);
    axis.reset(0.0, 0.0);
    axis.advance(1e-3, 1.0);  // kick
    const double dt = 1e-5;
    std::vector<double> y;
    for (int k = 0; k < 6000; ++k) {
      axis.advance(dt, 0.0);
      y.push_back(axis.position());
    }
    const double fd = 150.0 * std::sqrt(1.0 - 0.04 * 0.04);
    EXPECT_LT(relative_error(1.0 / mean_period(y, dt), fd), 2e-4) << "rk4=" << rk4;
  }
}

TEST(ResonantStageAxis, Rk4PathAgreesWithExactPath) {
  ResonantStageParameters p = table1_x();
  ResonantStageAxis exact(p);
  p.disturbance.sine_amplitude = 1e-300;
  p.disturbance.sine_frequency_hz = 1.0;
  ResonantStageAxis rk4(p);
  exact.reset(0.001, 0.0);
  rk4.reset(0.001, 0.0);
  for (int k = 0; k < 100; ++k) {
    const double force = 20.0 * std::sin(0.5 * k);
    exact.advance(1e-3, force);
    rk4.advance(1e-3, force);
  }
  EXPECT_NEAR(rk4.position(), exact.position(), 1e-13);
  EXPECT_NEAR(rk4.velocity(), exact.velocity(), 1e-10);
}

TEST(ResonantStageAxis, SineForceDisturbanceDrivesTheRigidBody) {
  // d(t) is a force in N added to the input; with no modes x'' = A sin(w t) / m.
  ResonantStageParameters p;
  p.mass = 24.0;
  p.disturbance.sine_amplitude = 3.0;
  p.disturbance.sine_frequency_hz = 2.0;
  ResonantStageAxis axis(p);
  axis.reset(0.0, 0.0);
  axis.advance(0.25, 0.0);
  // Rigid body only: x(t) = A/(m w) (t - sin(w t)/w).
  const double w = kTwoPi * 2.0, t = 0.25;
  EXPECT_LT(relative_error(axis.position(), 3.0 / (24.0 * w) * (t - std::sin(w * t) / w)), 1e-10);
  EXPECT_LT(relative_error(axis.velocity(), 3.0 / (24.0 * w) * (1.0 - std::cos(w * t))), 1e-10);
}

TEST(ResonantStageAxis, ResetPutsModesAtRest) {
  ResonantStageAxis axis(table1_x());
  axis.reset(0.0, 0.0);
  axis.advance(0.01, 100.0);
  axis.reset(0.2, -0.1);
  EXPECT_EQ(axis.position(), 0.2);
  EXPECT_EQ(axis.velocity(), -0.1);
  EXPECT_EQ(axis.time(), 0.0);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(axis.mode_state(i).norm(), 0.0);
}

TEST(ResonantStageAxis, SplitAdvanceEqualsSingleAdvance) {
  ResonantStageAxis whole(table1_x());
  ResonantStageAxis split(table1_x());
  whole.reset(0.0, 0.0);
  split.reset(0.0, 0.0);
  for (int k = 0; k < 100; ++k) {
    const double force = std::cos(0.9 * k);
    whole.advance(2e-4, force);
    split.advance(7e-5, force);
    split.advance(2e-4 - 7e-5, force);
  }
  EXPECT_LT(relative_error(split.position(), whole.position()), 1e-12);
  EXPECT_LT(relative_error(split.velocity(), whole.velocity()), 1e-12);
}

TEST(ResonantStageAxis, RejectsBadParameters) {
  auto check = [](ResonantStageParameters p, const std::string& name) {
    try {
      ResonantStageAxis axis(p);
      ADD_FAILURE() << "no throw for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  ResonantStageParameters p = table1_x();
  p.mass = 0.0;
  check(p, "mass");
  p = table1_x();
  p.modes[1].frequency_hz = 0.0;
  check(p, "modes[1].frequency_hz");
  p = table1_x();
  p.modes[2].damping_ratio = -0.01;
  check(p, "modes[2].damping_ratio");
  p = table1_x();
  p.modes[0].gain = std::nan("");
  check(p, "modes[0].gain");
}

TEST(ResonantStageAxis, CloneAndDescribe) {
  ResonantStageAxis axis(table1_x());
  axis.reset(0.0, 0.0);
  axis.advance(1e-3, 10.0);
  auto copy = axis.clone();
  EXPECT_EQ(copy->position(), axis.position());
  copy->advance(1e-3, -3.0);
  axis.advance(1e-3, -3.0);
  EXPECT_EQ(copy->position(), axis.position());
  EXPECT_EQ(copy->velocity(), axis.velocity());
  const std::string text = axis.describe();
  EXPECT_NE(text.find("m=24"), std::string::npos) << text;
  EXPECT_NE(text.find("f=510"), std::string::npos) << text;
}

}  // namespace
}  // namespace netmc::plant

#include "plant/flexible_linear_motor_axis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "plant/plant_catalog.hpp"

namespace netmc::plant {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The linear part only: no friction, no cogging, no viscous term unless a test sets one.
FlexibleLinearMotorParameters linear_axis() {
  FlexibleLinearMotorParameters p;
  p.motor.mass = 0.12;
  p.motor.damping = 0.0;
  p.motor.coulomb = 0.0;
  p.motor.stribeck_extra = 0.0;
  p.motor.cogging.clear();
  p.load_fraction = 0.3;
  p.mode_frequency_hz = 150.0;
  p.mode_damping_ratio = 0.05;
  p.current_loop_hz = 1500.0;
  p.max_substep_s = 1e-5;
  return p;
}

double centre_of_mass(const FlexibleLinearMotorAxis& a) {
  return (a.motor_mass() * a.motor_position() + a.load_mass() * a.position()) /
         (a.motor_mass() + a.load_mass());
}

TEST(FlexibleLinearMotorAxis, MassSplitAndModeCoefficients) {
  const FlexibleLinearMotorAxis axis(linear_axis());
  EXPECT_NEAR(axis.load_mass(), 0.036, 1e-15);
  EXPECT_NEAR(axis.motor_mass(), 0.084, 1e-15);
  // q'' + 2 zeta w q' + w^2 q with the reduced mass M_m M_l / M.
  const double w = kTwoPi * 150.0;
  const double reduced = 0.084 * 0.036 / 0.12;
  EXPECT_NEAR(axis.stiffness(), w * w * reduced, 1e-9 * w * w * reduced);
  EXPECT_NEAR(axis.mode_damping(), 2.0 * 0.05 * w * reduced, 1e-12);
}

TEST(FlexibleLinearMotorAxis, CurrentLoopLagMatchesClosedForm) {
  // Without friction and viscous damping the internal spring cancels in the centre of mass:
  // M x_c'' = f, tau f' = u - f, so from rest under a step u
  //   f(t) = u (1 - e^{-t/tau}),  x_c(t) = u/M (t^2/2 - tau t + tau^2 (1 - e^{-t/tau})).
  const FlexibleLinearMotorParameters p = linear_axis();
  FlexibleLinearMotorAxis axis(p);
  axis.reset(0.0, 0.0);
  const double u = 0.5;
  const double tau = 1.0 / (kTwoPi * p.current_loop_hz);
  // RK4 at h = 1e-5 s (h / tau = 0.094) is within 1e-6 relative of the exponentials.
  for (int k = 1; k <= 50; ++k) {
    axis.advance(2e-5, u);
    const double t = k * 2e-5;
    const double lag = -std::expm1(-t / tau);
    EXPECT_NEAR(axis.drive_force(), u * lag, 1e-6 * u) << t;
    const double xc = u / p.motor.mass * (t * t / 2.0 - tau * t + tau * tau * lag);
    EXPECT_NEAR(centre_of_mass(axis), xc, 1e-5 * u / p.motor.mass * t * t / 2.0) << t;
  }
  // One time constant: 63.2 % of the step, the 1.5 kHz bandwidth of appendix A.
  FlexibleLinearMotorAxis fresh(p);
  fresh.reset(0.0, 0.0);
  fresh.advance(tau, u);
  EXPECT_NEAR(fresh.drive_force() / u, 1.0 - std::exp(-1.0), 1e-6);
}

TEST(FlexibleLinearMotorAxis, FreeModeRingsAtItsFrequencyAndDamping) {
  // After a kick, with the drive force decayed, q = x_m - x_l rings freely:
  //   q(s) = e^{-zeta w s} (q0 cos wd s + (q0' + zeta w q0)/wd sin wd s).
  const FlexibleLinearMotorParameters p = linear_axis();
  FlexibleLinearMotorAxis axis(p);
  axis.reset(0.0, 0.0);
  axis.advance(1e-3, 1.0);
  axis.advance(5e-3, 0.0);  // 5 ms = 47 current-loop time constants: f ~ 1e-20 V
  ASSERT_LT(std::abs(axis.drive_force()), 1e-15);
  const double q0 = axis.motor_position() - axis.position();
  const double qd0 = axis.motor_velocity() - axis.velocity();
  ASSERT_GT(std::abs(q0) + std::abs(qd0) / (kTwoPi * 150.0), 1e-9);
  const double w = kTwoPi * p.mode_frequency_hz;
  const double z = p.mode_damping_ratio;
  const double wd = w * std::sqrt(1.0 - z * z);
  const double scale = std::abs(q0) + std::abs(qd0) / w;
  for (int k = 1; k <= 200; ++k) {
    axis.advance(1e-4, 0.0);
    const double s = k * 1e-4;
    const double q = std::exp(-z * w * s) * (q0 * std::cos(wd * s) + (qd0 + z * w * q0) / wd * std::sin(wd * s));
    ASSERT_NEAR(axis.motor_position() - axis.position(), q, 1e-7 * scale) << s;
  }
}

TEST(FlexibleLinearMotorAxis, UndampedEnergyIsConserved) {
  // zeta = 0, B = 0, no friction: after the drive force has died out, kinetic plus spring energy
  // stays constant.
  FlexibleLinearMotorParameters p = linear_axis();
  p.mode_damping_ratio = 0.0;
  FlexibleLinearMotorAxis axis(p);
  axis.reset(0.0, 0.0);
  axis.advance(1e-3, 1.0);
  axis.advance(5e-3, 0.0);
  auto energy = [&] {
    const double q = axis.motor_position() - axis.position();
    return 0.5 * axis.motor_mass() * axis.motor_velocity() * axis.motor_velocity() +
           0.5 * axis.load_mass() * axis.velocity() * axis.velocity() + 0.5 * axis.stiffness() * q * q;
  };
  const double e0 = energy();
  ASSERT_GT(e0, 0.0);
  for (int k = 0; k < 1000; ++k) axis.advance(1e-3, 0.0);
  EXPECT_NEAR(energy(), e0, 1e-6 * e0);
}

TEST(FlexibleLinearMotorAxis, ConstantCommandReachesTheRigidTerminalVelocity) {
  // With viscous friction B the steady state is x' = u / B on both masses, spring relaxed.
  FlexibleLinearMotorParameters p = linear_axis();
  p.motor.damping = 0.3;
  FlexibleLinearMotorAxis axis(p);
  axis.reset(0.0, 0.0);
  for (int k = 0; k < 5000; ++k) axis.advance(1e-3, 0.6);  // 5 s = 12 mechanical time constants
  EXPECT_NEAR(axis.velocity(), 2.0, 1e-4);
  EXPECT_NEAR(axis.motor_velocity(), 2.0, 1e-4);
  EXPECT_NEAR(axis.drive_force(), 0.6, 1e-12);
  EXPECT_NEAR(axis.motor_position() - axis.position(), 0.0, 1e-9);
}

TEST(FlexibleLinearMotorAxis, StribeckFrictionHoldsMoreAtRestThanAtSpeed) {
  // Thesis A.3: static level fc + (fs - fc) near rest, Coulomb fc well above the Stribeck speed.
  FlexibleLinearMotorParameters p = linear_axis();
  p.motor.coulomb = 0.1;
  p.motor.stribeck_extra = 0.05;
  p.motor.stribeck_velocity = 0.01;
  const LinearMotorAxis rigid(p.motor);
  EXPECT_NEAR(rigid.friction_force(10.0 * p.motor.friction_smoothing_velocity), 0.15, 1e-3);
  EXPECT_NEAR(rigid.friction_force(0.1), 0.1, 1e-12);
  EXPECT_NEAR(rigid.friction_force(-0.1), -0.1, 1e-12);
  // A command between fc and fs barely creeps (on the tanh's slope); one above fs breaks away.
  FlexibleLinearMotorAxis held(p);
  held.reset(0.0, 0.0);
  for (int k = 0; k < 500; ++k) held.advance(1e-3, 0.13);
  EXPECT_LT(held.velocity(), 5.0 * p.motor.friction_smoothing_velocity);
  FlexibleLinearMotorAxis moving(p);
  moving.reset(0.0, 0.0);
  for (int k = 0; k < 500; ++k) moving.advance(1e-3, 0.17);
  EXPECT_GT(moving.velocity(), 0.05);
}

TEST(FlexibleLinearMotorAxis, CloneKeepsTheWholeState) {
  FlexibleLinearMotorAxis axis(linear_axis());
  axis.reset(0.01, 0.0);
  axis.advance(3e-4, 1.0);
  auto copy = axis.clone();
  copy->advance(1e-3, -0.5);
  axis.advance(1e-3, -0.5);
  EXPECT_EQ(copy->position(), axis.position());
  EXPECT_EQ(copy->velocity(), axis.velocity());
}

TEST(FlexibleLinearMotorAxis, BadParametersAreRejectedByName) {
  auto message = [](FlexibleLinearMotorParameters p) -> std::string {
    try {
      FlexibleLinearMotorAxis axis(p);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  FlexibleLinearMotorParameters p = linear_axis();
  p.load_fraction = 1.0;
  EXPECT_NE(message(p).find("load_fraction"), std::string::npos);
  p = linear_axis();
  p.mode_frequency_hz = 0.0;
  EXPECT_NE(message(p).find("mode_frequency_hz"), std::string::npos);
  p = linear_axis();
  p.mode_damping_ratio = -0.1;
  EXPECT_NE(message(p).find("mode_damping_ratio"), std::string::npos);
  p = linear_axis();
  p.current_loop_hz = std::nan("");
  EXPECT_NE(message(p).find("current_loop_hz"), std::string::npos);
  p = linear_axis();
  p.max_substep_s = 0.0;
  EXPECT_NE(message(p).find("max_substep_s"), std::string::npos);
  p = linear_axis();
  p.motor.mass = -1.0;
  EXPECT_NE(message(p).find("mass"), std::string::npos);
}

TEST(FlexibleLinearMotorAxis, CatalogOverridesByKey) {
  const auto keys = plant_parameters("linmotor-flex");
  for (const char* key : {"mode_frequency_hz", "mode_damping", "load_fraction", "current_loop_hz", "stribeck_extra_v",
                          "load_v_s2_m", "mass_v_s2_m"}) {
    bool found = false;
    for (const auto& k : keys) found = found || k.key == key;
    EXPECT_TRUE(found) << key;
  }
  AxisOverrides y;
  y.parameters = {{"mode_frequency_hz", 45.0}, {"mode_damping", 0.2}, {"current_loop_hz", 1200.0}};
  AxisSet set = make_plant_set("linmotor-flex", 2, {AxisOverrides{}, y});
  const std::string x_text = set.axes[0]->describe();
  const std::string y_text = set.axes[1]->describe();
  EXPECT_NE(x_text.find("mode 150 Hz zeta 0.45"), std::string::npos) << x_text;
  EXPECT_NE(y_text.find("mode 45 Hz zeta 0.2"), std::string::npos) << y_text;
  EXPECT_NE(y_text.find("current loop 1200 Hz"), std::string::npos) << y_text;
  // A payload rides on the carriage: total and carriage mass both grow by it.
  AxisOverrides payload;
  payload.parameters = {{"load_v_s2_m", 0.07}};
  AxisSet loaded = make_plant_set("linmotor-flex", 1, {payload});
  const auto& flex = dynamic_cast<const FlexibleLinearMotorAxis&>(*loaded.axes[0]);
  const AxisSet nominal = make_plant_set("linmotor-flex", 1);
  const auto& bare = dynamic_cast<const FlexibleLinearMotorAxis&>(*nominal.axes[0]);
  EXPECT_NEAR(flex.load_mass(), bare.load_mass() + 0.07, 1e-12);
  EXPECT_NEAR(flex.motor_mass(), bare.motor_mass(), 1e-12);
  AxisOverrides bad;
  bad.parameters = {{"load_fraction", 1.5}};
  EXPECT_THROW(make_plant_set("linmotor-flex", 1, {bad}), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::plant

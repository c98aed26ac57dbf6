#include "plant/dead_zone_input.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "plant/plant_catalog.hpp"
#include "plant/second_order_axis.hpp"

namespace netmc::plant {
namespace {

// Thesis eq. 5-51 (Exp I), in volts.
constexpr DeadZoneParameters kExpI{1.2, -1.0, 0.9, 1.0};

TEST(DeadZoneInput, ThreePiecesOfEq52) {
  EXPECT_EQ(dead_zone_output(kExpI, 1.2), 0.0);
  EXPECT_DOUBLE_EQ(dead_zone_output(kExpI, 2.2), 0.9);
  EXPECT_DOUBLE_EQ(dead_zone_output(kExpI, 5.0), 0.9 * 3.8);
  for (double v : {-0.999, -0.5, 0.0, 0.7, 1.1999}) EXPECT_EQ(dead_zone_output(kExpI, v), 0.0) << v;
  EXPECT_EQ(dead_zone_output(kExpI, -1.0), 0.0);
  EXPECT_DOUBLE_EQ(dead_zone_output(kExpI, -3.0), -2.0);
  EXPECT_DOUBLE_EQ(dead_zone_output({0.0, 0.0, 1.0, 1.0}, -0.3), -0.3);  // no gap: identity
}

TEST(DeadZoneInput, ValidationNamesTheField) {
  auto message = [](DeadZoneParameters p) {
    try {
      validate_dead_zone(p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({-0.1, -1.0, 1.0, 1.0}).find("right_break_v"), std::string::npos);
  EXPECT_NE(message({1.0, 0.1, 1.0, 1.0}).find("left_break_v"), std::string::npos);
  EXPECT_NE(message({1.0, NAN, 1.0, 1.0}).find("left_break_v"), std::string::npos);
  EXPECT_NE(message({1.0, -1.0, 0.0, 1.0}).find("right_slope"), std::string::npos);
  EXPECT_NE(message({1.0, -1.0, 1.0, INFINITY}).find("left_slope"), std::string::npos);
  EXPECT_EQ(message({0.0, 0.0, 1.0, 1.0}), "");
  EXPECT_THROW(DeadZoneInput(kExpI, nullptr), std::invalid_argument);
}

TEST(DeadZoneInput, HeldInputInsideTheGapLeavesThePlantAtRest) {
  AxisSet set = make_plant_set("hiwin", 1);
  ASSERT_EQ(set.axes.size(), 1u);
  AxisPlant& axis = *set.axes[0];
  axis.reset(0.0, 0.0);
  for (double v : {1.19, -0.99, 0.5}) {
    for (int k = 0; k < 500; ++k) axis.advance(2e-4, v);
    EXPECT_EQ(axis.position(), 0.0) << v;
    EXPECT_EQ(axis.velocity(), 0.0) << v;
  }
  EXPECT_NEAR(axis.time(), 0.3, 1e-12);
}

TEST(DeadZoneInput, HiwinWithoutFrictionIsAFirstOrderVelocitySystem) {
  // A = 0, v = 2 V held: w = 0.9 (2 - 1.2) = 0.72 V, x'' = -4.3 x' + 3.6 w; from rest
  // x(t) = (c / B) (t - (1 - e^(-B t)) / B), c = E w.
  AxisOverrides no_friction;
  no_friction.parameters = {{"coulomb_m_s2", 0.0}};
  AxisSet set = make_plant_set("hiwin", 1, {no_friction});
  AxisPlant& axis = *set.axes[0];
  const double b = 4.3, c = 3.6 * 0.9 * (2.0 - 1.2);
  for (int k = 1; k <= 100; ++k) {
    axis.advance(0.01, 2.0);
    const double t = 0.01 * k;
    const double x = c / b * (t - (1.0 - std::exp(-b * t)) / b);
    const double v = c / b * (1.0 - std::exp(-b * t));
    ASSERT_NEAR(axis.position(), x, 1e-12 + 1e-10 * x) << t;
    ASSERT_NEAR(axis.velocity(), v, 1e-12 + 1e-10 * v) << t;
  }
  // Left piece, Exp II's symmetric slope: w = 0.9 (-3 + 1) = -1.8 V.
  AxisOverrides symmetric;
  symmetric.parameters = {{"coulomb_m_s2", 0.0}, {"dead_zone_left_slope", 0.9}};
  AxisSet left = make_plant_set("hiwin", 1, {symmetric});
  left.axes[0]->advance(0.5, -3.0);
  const double cl = 3.6 * -1.8;
  EXPECT_NEAR(left.axes[0]->velocity(), cl / b * (1.0 - std::exp(-b * 0.5)), 1e-12);
}

TEST(DeadZoneInput, HiwinFrictionOpposesMotionWithLevelA) {
  // Coasting at 0.1 m/s with v = 0: x'' = -B x' - A (tanh ~ 1), so after 1 ms the velocity is
  // close to the closed form of the saturated friction.
  AxisSet set = make_plant_set("hiwin", 1);
  AxisPlant& axis = *set.axes[0];
  axis.reset(0.0, 0.1);
  axis.advance(1e-3, 0.0);
  const double b = 4.3, a = 0.9;
  const double expected = (0.1 + a / b) * std::exp(-b * 1e-3) - a / b;
  EXPECT_NEAR(axis.velocity(), expected, 1e-12);
}

TEST(DeadZoneInput, KeysUnitsAndDisturbanceInVolts) {
  bool found = false;
  for (const auto& p : plant_parameters("hiwin")) {
    if (p.key == "dead_zone_left_slope") found = true;
  }
  EXPECT_TRUE(found);
  EXPECT_EQ(plant_input_unit("hiwin"), "V");
  // A constant disturbance of 0.5 V acts behind the dead zone: E * 0.5 m/s^2 with v = 0.
  AxisOverrides pushed;
  pushed.parameters = {{"coulomb_m_s2", 0.0}};
  pushed.disturbance.constant = 0.5;
  AxisSet set = make_plant_set("hiwin", 1, {pushed});
  set.axes[0]->advance(0.2, 0.0);
  EXPECT_NEAR(set.axes[0]->velocity(), 3.6 * 0.5 / 4.3 * (1.0 - std::exp(-4.3 * 0.2)), 1e-12);
  EXPECT_THROW(make_plant_set("hiwin", 1, {{{{"dead_zone_right_slope", -1.0}}, {}}}), std::invalid_argument);
  auto copy = set.axes[0]->clone();
  EXPECT_EQ(copy->describe(), set.axes[0]->describe());
  EXPECT_NE(copy->describe().find("dead zone"), std::string::npos);
}

}  // namespace
}  // namespace netmc::plant

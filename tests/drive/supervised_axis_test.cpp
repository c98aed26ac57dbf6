// The axis above the drive seam with netmc's simulated drive below: the in-period input switch
// (paper 001, eq. 4), stale setpoints, the job's clamp, the operator's trips, the slew limit and
// the quick stop a trip commands.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "plant/second_order_axis.hpp"
#include "server/drive/simulated_drive.hpp"
#include "server/drive/supervised_axis.hpp"
#include "tests/drive/power_state_printer.hpp"
#include "tests/drive/linear_servo_plant.hpp"

namespace netmc::drive {
namespace {

std::shared_ptr<SimulatedDrive> linear_drive() {
  auto drive = std::make_shared<SimulatedDrive>(linear_servo_plant(), "sim:test");
  drive->open();
  return drive;
}

SupervisedAxis linear_axis(double command_limit = 1e9, AxisLimits limits = {}) {
  return SupervisedAxis(linear_drive(), command_limit, limits);
}

TEST(SupervisedAxis, SetpointActsFromItsArrivalWithinThePeriod) {
  // From rest with u(k-1) = 0 and u(k) = 1 arriving at tau: paper 001, eq. 4 gives
  // x2(k+1) = b/a2 (e^{a2 (h - tau)} - 1).
  const double h = 0.005, tau = 0.0012, a2 = -20.0, b = 20.0;
  SupervisedAxis axis = linear_axis();
  axis.begin_iteration(0.0);
  EXPECT_EQ(axis.power_state(), PowerState::operation_enabled);
  axis.advance_to(h, {{0.0, tau, 0, 1.0}});
  EXPECT_NEAR(axis.reading().velocity_m_s, b / a2 * (std::exp(a2 * (h - tau)) - 1.0), 1e-14);
  EXPECT_EQ(axis.input(), 1.0);
}

TEST(SupervisedAxis, StaleSetpointsDoNotActAndTheJobsSaturationClamps) {
  SupervisedAxis axis = linear_axis(0.5);
  axis.begin_iteration(0.0);
  axis.advance_to(0.005, {{0.0, 0.001, 2, 3.0}, {0.0, 0.002, 1, -3.0}});
  EXPECT_EQ(axis.input(), 0.5);  // clamped, and sequence 1 arrived after 2: dropped
  EXPECT_EQ(axis.stale_setpoints(), 1u);
}

// The operator's limits trip the axis: the drive quick-stops, nothing that comes next acts, a new
// iteration does not clear the fault; the operator's reset does, and the next iteration runs.
TEST(SupervisedAxis, OperatorLimitsTripTheAxisIntoAQuickStopAndTheFaultLatches) {
  AxisLimits limits;
  limits.command = 2.0;
  SupervisedAxis axis = linear_axis(1e9, limits);
  axis.begin_iteration(0.0);
  axis.advance_to(0.005, {{0.0, 0.001, 0, 1.5}});
  EXPECT_FALSE(axis.fault());
  EXPECT_EQ(axis.input(), 1.5);
  axis.advance_to(0.010, {{0.005, 0.006, 1, 1e30}});
  ASSERT_TRUE(axis.fault());
  EXPECT_NE(axis.fault()->find("command 1e+30 (cycle 1) beyond the axis's limit 2"), std::string::npos) << *axis.fault();
  EXPECT_EQ(axis.power_state(), PowerState::fault_reaction_active);  // the drive ramps down
  EXPECT_FALSE(axis.running());
  axis.advance_to(0.015, {{0.010, 0.011, 2, 1.0}});  // a good command after the trip: ignored
  EXPECT_EQ(axis.input(), 1.5);
  axis.finish_reaction();
  EXPECT_EQ(axis.power_state(), PowerState::fault);
  EXPECT_LT(std::abs(axis.reading().velocity_m_s), 1e-3);
  axis.begin_iteration(0.0);
  EXPECT_TRUE(axis.fault());
  EXPECT_FALSE(axis.running());
  axis.clear_fault();
  EXPECT_EQ(axis.power_state(), PowerState::switch_on_disabled);
  axis.begin_iteration(0.0);
  EXPECT_EQ(axis.power_state(), PowerState::operation_enabled);
  axis.advance_to(0.005, {{0.0, 0.001, 0, 1.0}});
  EXPECT_EQ(axis.input(), 1.0);

  // NaN: a fault, not a NaN plant.
  SupervisedAxis nan_axis = linear_axis(1e9, limits);
  nan_axis.begin_iteration(0.0);
  nan_axis.advance_to(0.005, {{0.0, 0.001, 0, std::nan("")}});
  EXPECT_TRUE(nan_axis.fault());
  EXPECT_TRUE(std::isfinite(nan_axis.reading().position_m));
}

TEST(SupervisedAxis, LeavingTheTravelWindowOrExceedingTheVelocityTrips) {
  // u = 1 drives the axis towards b/|a2| = 1 m/s with a 50 ms time constant: it passes 0.5 m/s
  // after ln 2 / 20 = 34.7 ms.
  AxisLimits window;
  window.position_min_m = -0.005;
  window.position_max_m = 0.005;
  SupervisedAxis axis = linear_axis(1e9, window);
  axis.begin_iteration(0.0);
  double tripped_at = -1.0;
  axis.advance_to(0.001, {{0.0, 0.0, 0, 1.0}});
  for (int k = 2; k <= 100 && tripped_at < 0.0; ++k) {
    axis.advance_to(0.001 * k, {});
    if (axis.fault()) tripped_at = 0.001 * k;
  }
  ASSERT_GT(tripped_at, 0.0);
  EXPECT_NE(axis.fault()->find("outside the window [-0.005, 0.005] m"), std::string::npos) << *axis.fault();
  // The first 1 ms sample at which the closed-form step response x(t) = t - (1 - e^{-20 t}) / 20
  // is beyond 5 mm (24.1 ms, so 25 ms).
  double expected = 0.0;
  for (int k = 1; expected == 0.0; ++k) {
    const double t = 0.001 * k;
    if (t - (1.0 - std::exp(-20.0 * t)) / 20.0 > 0.005) expected = t;
  }
  EXPECT_NEAR(tripped_at, expected, 1e-12);

  AxisLimits speed;
  speed.velocity_m_s = 0.5;
  SupervisedAxis fast = linear_axis(1e9, speed);
  fast.begin_iteration(0.0);
  fast.advance_to(0.001, {{0.0, 0.0, 0, 1.0}});
  double fast_trip = -1.0;
  for (int k = 2; k <= 100 && fast_trip < 0.0; ++k) {
    fast.advance_to(0.001 * k, {});
    if (fast.fault()) fast_trip = 0.001 * k;
  }
  EXPECT_NEAR(fast_trip, std::log(2.0) / 20.0, 0.0011);
  EXPECT_NE(fast.fault()->find("velocity"), std::string::npos);
}

// A trip is not a cut command: the drive brings the axis to standstill on the quick stop ramp.
// From 0.8 m/s at 4 m/s^2 the ramp takes 0.2 s and covers v^2 / 2a = 80 mm; a cut command would
// let this plant coast v / 20 = 40 mm in an exponential decay that is 1.5 % of v after 0.2 s.
TEST(SupervisedAxis, ATripDeceleratesOnTheQuickStopRampToStandstill) {
  AxisLimits window;
  window.position_min_m = -1.0;
  window.position_max_m = 0.4;
  auto drive = linear_drive();
  drive->write_quick_stop_deceleration(4.0);
  SupervisedAxis axis(drive, 1e9, window);
  axis.begin_iteration(0.0);
  axis.advance_to(0.001, {{0.0, 0.0, 0, 0.8}});
  double t = 0.001;
  while (!axis.fault() && t < 2.0) {
    t += 0.001;
    axis.advance_to(t, {});
  }
  ASSERT_TRUE(axis.fault());
  const double trip_time = t, x0 = axis.reading().position_m, v0 = axis.reading().velocity_m_s;
  EXPECT_NEAR(v0, 0.8, 0.01);
  double worst_lag = 0.0;
  while (axis.power_state() == PowerState::fault_reaction_active && t < trip_time + 2.0) {
    t += 0.001;
    axis.sample(t);
    const double ramp = std::max(0.0, v0 - 4.0 * (t - trip_time));
    if (t > trip_time + 0.02) worst_lag = std::max(worst_lag, std::abs(axis.reading().velocity_m_s - ramp));
  }
  EXPECT_EQ(axis.power_state(), PowerState::fault);
  EXPECT_LT(worst_lag, 0.02);  // within 2.5 % of v0 once the loop has caught the ramp
  EXPECT_NEAR(t - trip_time, 0.2, 0.03);
  EXPECT_NEAR(axis.reading().position_m - x0, v0 * v0 / 8.0, 0.004);
}

TEST(SupervisedAxis, SlewLimitRampsAStepInsteadOfTripping) {
  AxisLimits limits;
  limits.slew_per_s = 100.0;  // 0.1 per millisecond
  SupervisedAxis axis = linear_axis(1e9, limits);
  axis.begin_iteration(0.0);
  axis.advance_to(0.005, {{0.0, 0.004, 0, 1.0}});  // 4 ms after the last change: at most 0.4
  EXPECT_NEAR(axis.input(), 0.4, 1e-12);
  axis.advance_to(0.010, {{0.005, 0.006, 1, 1.0}});  // 2 ms later: 0.6
  EXPECT_NEAR(axis.input(), 0.6, 1e-12);
  EXPECT_FALSE(axis.fault());
}

TEST(SupervisedAxis, TheWatchdogsQuickStopIsNoFault) {
  SupervisedAxis axis = linear_axis();
  axis.begin_iteration(0.0);
  axis.advance_to(0.005, {{0.0, 0.0, 0, 0.5}});
  axis.quick_stop();
  EXPECT_EQ(axis.power_state(), PowerState::quick_stop_active);
  axis.advance_to(0.010, {{0.005, 0.006, 1, 1.0}});
  EXPECT_EQ(axis.input(), 0.5);  // not applied
  axis.finish_reaction();
  EXPECT_EQ(axis.power_state(), PowerState::switch_on_disabled);
  EXPECT_FALSE(axis.fault());
  axis.begin_iteration(0.0);  // the next iteration enables it again
  EXPECT_EQ(axis.power_state(), PowerState::operation_enabled);
}

TEST(AxisLimits, BadLimitsNameTheirFlag) {
  AxisLimits limits;
  limits.command = 0.0;
  EXPECT_THROW(limits.validate(), std::invalid_argument);
  limits = {};
  limits.position_min_m = 0.2;
  limits.position_max_m = 0.1;
  try {
    limits.validate();
    ADD_FAILURE() << "an empty window was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("--position-window"), std::string::npos);
  }
  EXPECT_EQ(AxisLimits{}.describe(), "none");
  AxisLimits own;
  own.command = 3.0;
  AxisLimits fallback;
  fallback.command = 5.0;
  fallback.velocity_m_s = 0.2;
  const AxisLimits merged = own.or_else(fallback);
  EXPECT_EQ(merged.command, 3.0);
  EXPECT_EQ(merged.velocity_m_s, 0.2);
  EXPECT_TRUE(std::isinf(merged.slew_per_s));
}

}  // namespace
}  // namespace netmc::drive

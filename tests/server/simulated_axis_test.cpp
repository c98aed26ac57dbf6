// The event-driven actuator: in-period input switch (paper 001, eq. 4) and limits at the axis.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "plant/second_order_axis.hpp"
#include "server/sim/simulated_axis.hpp"

namespace netmc::sim {
namespace {

SimulatedAxis linear_axis(double command_limit = 1e9, AxisLimits limits = {}) {
  plant::SecondOrderAxisParameters p;
  p.a1 = 0.0;
  p.a2 = -20.0;
  p.b = 20.0;
  return SimulatedAxis(std::make_unique<plant::SecondOrderAxis>(p),
                       plant::PositionSensor({}, 1, 0), command_limit, limits);
}

TEST(SimulatedAxis, SetpointActsFromItsArrivalWithinThePeriod) {
  // From rest with u(k-1) = 0 and u(k) = 1 arriving at tau: paper 001, eq. 4 gives
  // x2(k+1) = b/a2 (e^{a2 (h - tau)} - 1).
  const double h = 0.005, tau = 0.0012, a2 = -20.0, b = 20.0;
  SimulatedAxis axis = linear_axis();
  axis.reset(0.0);
  axis.advance_to(h, {{0.0, tau, 0, 1.0}});
  EXPECT_NEAR(axis.plant().velocity(), b / a2 * (std::exp(a2 * (h - tau)) - 1.0), 1e-14);
  EXPECT_EQ(axis.input(), 1.0);
}

TEST(SimulatedAxis, StaleSetpointsDoNotActAndLimitsAreEnforced) {
  SimulatedAxis axis = linear_axis(0.5);
  axis.reset(0.0);
  axis.advance_to(0.005, {{0.0, 0.001, 2, 3.0}, {0.0, 0.002, 1, -3.0}});
  EXPECT_EQ(axis.input(), 0.5);  // clamped, and sequence 1 arrived after 2: dropped
  EXPECT_EQ(axis.stale_setpoints(), 1u);
}

// The operator's limits trip the axis: the command goes to zero and stays there, whatever comes
// next, until the operator clears the fault. A new iteration does not clear it.
TEST(SimulatedAxis, OperatorLimitsTripTheAxisAndTheFaultLatches) {
  AxisLimits limits;
  limits.command = 2.0;
  SimulatedAxis axis = linear_axis(1e9, limits);
  axis.reset(0.0);
  axis.advance_to(0.005, {{0.0, 0.001, 0, 1.5}});
  EXPECT_FALSE(axis.fault());
  EXPECT_EQ(axis.input(), 1.5);
  axis.advance_to(0.010, {{0.005, 0.006, 1, 1e30}});
  ASSERT_TRUE(axis.fault());
  EXPECT_NE(axis.fault()->find("command 1e+30 (cycle 1) beyond the axis's limit 2"), std::string::npos) << *axis.fault();
  EXPECT_EQ(axis.input(), 0.0);
  axis.advance_to(0.015, {{0.010, 0.011, 2, 1.0}});  // a good command after the trip: ignored
  EXPECT_EQ(axis.input(), 0.0);
  axis.reset(0.0);
  EXPECT_TRUE(axis.fault());
  axis.clear_fault();
  axis.advance_to(0.005, {{0.0, 0.001, 0, 1.0}});
  EXPECT_EQ(axis.input(), 1.0);

  // NaN: a fault, not a NaN plant.
  SimulatedAxis nan_axis = linear_axis(1e9, limits);
  nan_axis.reset(0.0);
  nan_axis.advance_to(0.005, {{0.0, 0.001, 0, std::nan("")}});
  EXPECT_TRUE(nan_axis.fault());
  EXPECT_TRUE(std::isfinite(nan_axis.plant().position()));
}

TEST(SimulatedAxis, LeavingTheTravelWindowOrExceedingTheVelocityTrips) {
  // u = 1 drives the axis towards b/|a2| = 1 m/s with a 50 ms time constant: it passes 0.5 m/s
  // after ln 2 / 20 = 34.7 ms.
  AxisLimits window;
  window.position_min_m = -0.005;
  window.position_max_m = 0.005;
  SimulatedAxis axis = linear_axis(1e9, window);
  axis.reset(0.0);
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
  EXPECT_EQ(axis.input(), 0.0);

  AxisLimits speed;
  speed.velocity_m_s = 0.5;
  SimulatedAxis fast = linear_axis(1e9, speed);
  fast.reset(0.0);
  fast.advance_to(0.001, {{0.0, 0.0, 0, 1.0}});
  double fast_trip = -1.0;
  for (int k = 2; k <= 100 && fast_trip < 0.0; ++k) {
    fast.advance_to(0.001 * k, {});
    if (fast.fault()) fast_trip = 0.001 * k;
  }
  EXPECT_NEAR(fast_trip, std::log(2.0) / 20.0, 0.0011);
  EXPECT_NE(fast.fault()->find("velocity"), std::string::npos);
}

TEST(SimulatedAxis, SlewLimitRampsAStepInsteadOfTripping) {
  AxisLimits limits;
  limits.slew_per_s = 100.0;  // 0.1 per millisecond
  SimulatedAxis axis = linear_axis(1e9, limits);
  axis.reset(0.0);
  axis.advance_to(0.005, {{0.0, 0.004, 0, 1.0}});  // 4 ms after the last change: at most 0.4
  EXPECT_NEAR(axis.input(), 0.4, 1e-12);
  axis.advance_to(0.010, {{0.005, 0.006, 1, 1.0}});  // 2 ms later: 0.6
  EXPECT_NEAR(axis.input(), 0.6, 1e-12);
  EXPECT_FALSE(axis.fault());
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
}

}  // namespace
}  // namespace netmc::sim

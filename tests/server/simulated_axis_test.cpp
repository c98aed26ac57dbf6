// The event-driven actuator: in-period input switch (paper 001, eq. 4) and limits at the axis.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/second_order_axis.hpp"
#include "server/sim/simulated_axis.hpp"

namespace netmc::sim {
namespace {

SimulatedAxis linear_axis(double command_limit = 1e9) {
  plant::SecondOrderAxisParameters p;
  p.a1 = 0.0;
  p.a2 = -20.0;
  p.b = 20.0;
  return SimulatedAxis(std::make_unique<plant::SecondOrderAxis>(p),
                       plant::PositionSensor({}, 1, 0), command_limit);
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

}  // namespace
}  // namespace netmc::sim

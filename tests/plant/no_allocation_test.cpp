// advance() runs ~10^6 times per study: it must not touch the heap. This binary replaces the
// global operator new to count allocations made while the plants step.

#include <gtest/gtest.h>

#include <cmath>

#include "plant/plant_catalog.hpp"
#include "plant/position_sensor.hpp"
#include "tests/support/allocation_counter.hpp"

namespace netmc::plant {
namespace {

TEST(NoAllocation, AdvanceAndMeasureDoNotAllocate) {
  for (const std::string& name : plant_names()) {
    AxisSet set = make_plant_set(name, 3);
    PositionSensor sensor({0.5e-6, 1e-7}, 3, 1);
    const long before = netmc::testing::heap_allocations();
    for (auto& axis : set.axes) {
      axis->reset(0.0, 0.0);
      for (int k = 0; k < 200; ++k) {
        // A different split every cycle: cache misses included.
        const double tau = 1e-4 + 1e-6 * k;
        axis->advance(tau, 0.1);
        axis->advance(1e-3 - tau, 0.2);
        (void)sensor.measure(axis->position());
      }
    }
    EXPECT_EQ(netmc::testing::heap_allocations() - before, 0) << name;
  }
}

}  // namespace
}  // namespace netmc::plant

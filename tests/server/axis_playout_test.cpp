// The axis's playout buffer (delay compensation): a setpoint planned for a later instant than its
// arrival acts at that instant, a late one on arrival, a stale one not at all, and no plan parks a
// command for more than AxisEndpoint::kMaxHoldS. Without plans nothing changes.
#include <gtest/gtest.h>

#include <limits>

#include "server/sim/axis_endpoint.hpp"
#include "sim_test_support.hpp"

namespace netmc::sim {
namespace {

// A 4 ms constant downlink on the small circle job's first axis.
ContourJob delayed_job() {
  ContourJob job = testing::small_circle_job();
  job.downlink.delay = netsim::make_constant_delay(0.004);
  return job;
}

TEST(AxisPlayout, AnEarlyArrivalActsAtItsPlannedInstantALateOneOnArrival) {
  const ContourJob job = delayed_job();
  AxisEndpoint axis(AxisEndpoint::simulated_drive(job, 0), job, 0);
  axis.begin_iteration(1, 0.06);
  axis.submit_setpoint(0.000, 0, 0.1, 0.009);  // arrives at 4 ms, planned for 9 ms: held
  axis.submit_setpoint(0.001, 1, 0.2, 0.002);  // arrives at 5 ms, planned for 2 ms: late, on arrival
  const auto& first = axis.advance_to(0.006);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].sequence, 1u);
  EXPECT_DOUBLE_EQ(first[0].arrival_time_s, 0.005);
  EXPECT_DOUBLE_EQ(first[0].network_arrival_s, 0.005);
  EXPECT_EQ(axis.next_arrival_s(), 0.009);  // the held one counts as arriving then
  const auto& second = axis.advance_to(0.010);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second[0].sequence, 0u);         // released at its instant...
  EXPECT_DOUBLE_EQ(second[0].arrival_time_s, 0.009);
  EXPECT_DOUBLE_EQ(second[0].network_arrival_s, 0.004);
  EXPECT_EQ(axis.stale_setpoints(), 1u);     // ...and dropped there: 1 was newer
}

TEST(AxisPlayout, NoPlanParksACommandLongerThanTheBound) {
  const ContourJob job = delayed_job();
  AxisEndpoint axis(AxisEndpoint::simulated_drive(job, 0), job, 0);
  axis.begin_iteration(1, 0.06);
  axis.submit_setpoint(0.0, 0, 0.1, 1e9);  // a faulty plan
  EXPECT_TRUE(axis.advance_to(0.5).empty());
  const auto& applied = axis.advance_to(2.0);
  ASSERT_EQ(applied.size(), 1u);
  EXPECT_DOUBLE_EQ(applied[0].arrival_time_s, 0.004 + AxisEndpoint::kMaxHoldS);
}

TEST(AxisPlayout, WithoutPlansSetpointsActOnArrivalAsBefore) {
  const ContourJob job = delayed_job();
  AxisEndpoint axis(AxisEndpoint::simulated_drive(job, 0), job, 0);
  axis.begin_iteration(1, 0.06);
  axis.submit_setpoint(0.0, 0, 0.1);
  axis.submit_setpoint(0.001, 1, 0.2, -std::numeric_limits<double>::infinity());
  const auto& applied = axis.advance_to(0.006);
  ASSERT_EQ(applied.size(), 2u);
  EXPECT_DOUBLE_EQ(applied[0].arrival_time_s, 0.004);
  EXPECT_DOUBLE_EQ(applied[1].arrival_time_s, 0.005);
  EXPECT_DOUBLE_EQ(applied[1].network_arrival_s, 0.005);
}

}  // namespace
}  // namespace netmc::sim

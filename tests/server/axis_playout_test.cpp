// The axis's playout buffer (delay compensation): a setpoint planned for a later instant than its
// arrival acts at that instant, a late one on arrival, a stale one not at all, and no plan parks a
// command for more than AxisEndpoint::kMaxHoldS. Without plans nothing changes. With packets
// (packetized predictive control) the axis plays, each period, the command meant for it from the
// freshest setpoint it holds: a lost setpoint's instants are covered by its predecessor's
// horizon, then its last command is held; each command is checked on arrival.
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

// h = 5 ms, 4 ms downlink; setpoint k leaves at 5k ms, planned for 5k + 5 ms (grid instants).
TEST(AxisPlayout, PacketsCoverALostSetpointFromTheHorizonThenHoldTheLastCommand) {
  const ContourJob job = delayed_job();
  AxisEndpoint axis(AxisEndpoint::simulated_drive(job, 0), job, 0);
  axis.begin_iteration(1, 0.06);
  ASSERT_TRUE(axis.submit_packet(0.000, 0, 0.005, {0.10, 0.11, 0.12}));
  // Setpoints 1 and 2 never reach the axis (not submitted: lost); 3 arrives in time for 20 ms.
  const auto& first = axis.advance_to(0.0149);  // instants 5 and 10 ms: 0's own and its U(1)
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].sequence, 0u);
  EXPECT_EQ(first[0].horizon_index, 0u);
  EXPECT_NEAR(first[0].arrival_time_s, 0.005, 1e-15);
  EXPECT_DOUBLE_EQ(first[0].network_arrival_s, 0.004);
  EXPECT_EQ(first[1].sequence, 0u);
  EXPECT_EQ(first[1].horizon_index, 1u);
  EXPECT_NEAR(first[1].arrival_time_s, 0.010, 1e-15);
  EXPECT_DOUBLE_EQ(axis.supervised().input(), 0.11);
  ASSERT_TRUE(axis.submit_packet(0.015, 3, 0.020, {0.30, 0.31}));  // arrives at 19 ms
  const auto& second = axis.advance_to(0.0249);  // 15 ms: U(2) of 0; 20 ms: 3's own
  ASSERT_EQ(second.size(), 2u);
  EXPECT_EQ(second[0].horizon_index, 2u);
  EXPECT_EQ(second[1].sequence, 3u);
  EXPECT_EQ(second[1].horizon_index, 0u);
  EXPECT_NEAR(second[1].arrival_time_s, 0.020, 1e-15);
  EXPECT_EQ(axis.horizon_cycles(), 2u);
  EXPECT_EQ(axis.held_cycles(), 0u);
  // 25 ms: 3's U(1); 30, 35, 40 ms: nothing left, 0.31 held at three instants.
  const auto& third = axis.advance_to(0.0449);
  ASSERT_EQ(third.size(), 1u);
  EXPECT_EQ(third[0].horizon_index, 1u);
  EXPECT_EQ(axis.horizon_cycles(), 3u);
  EXPECT_EQ(axis.held_cycles(), 3u);
  EXPECT_DOUBLE_EQ(axis.supervised().input(), 0.31);
  EXPECT_EQ(axis.stale_setpoints(), 0u);
}

TEST(AxisPlayout, ALatePacketStartsAtItsNextInstantAnOlderOneNeverPlaysOneBeyondItsHorizonHolds) {
  const ContourJob job = delayed_job();
  AxisEndpoint axis(AxisEndpoint::simulated_drive(job, 0), job, 0);
  axis.begin_iteration(1, 0.06);
  ASSERT_TRUE(axis.submit_packet(0.000, 0, 0.002, {0.10, 0.11, 0.12}));  // arrives at 4 ms, after 2 ms
  const auto& first = axis.advance_to(0.0099);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].horizon_index, 1u);  // its instant 2 ms is gone: U(1) at 7 ms
  EXPECT_NEAR(first[0].arrival_time_s, 0.007, 1e-15);
  ASSERT_TRUE(axis.submit_packet(0.010, 2, 0.017, {0.20}));   // arrives at 14 ms
  ASSERT_TRUE(axis.submit_packet(0.0105, 1, 0.012, {0.15}));  // arrives at 14.5 ms: older than 2
  const auto& second = axis.advance_to(0.0199);  // 12 ms: 0's U(2); 17 ms: 2's own
  ASSERT_EQ(second.size(), 2u);
  EXPECT_EQ(second[0].sequence, 0u);
  EXPECT_EQ(second[1].sequence, 2u);
  EXPECT_EQ(axis.stale_setpoints(), 1u);  // 1: its one command's period was over when it came
  // At 24 ms, its horizon over at 10 ms: the freshest all the same, its last command acts at its
  // next instant, 25 ms, and holds (counted held, and reported: the server learns its delay).
  ASSERT_TRUE(axis.submit_packet(0.020, 5, 0.0, {0.50, 0.51}));
  const std::uint64_t held_before = axis.held_cycles();
  const auto& third = axis.advance_to(0.0251);
  ASSERT_FALSE(third.empty());
  EXPECT_EQ(third.back().sequence, 5u);
  EXPECT_EQ(third.back().horizon_index, 1u);
  EXPECT_NEAR(third.back().arrival_time_s, 0.025, 1e-15);
  EXPECT_DOUBLE_EQ(third.back().network_arrival_s, 0.024);
  EXPECT_DOUBLE_EQ(axis.supervised().input(), 0.51);
  EXPECT_EQ(axis.held_cycles(), held_before + 2);  // 22 ms (2's one command held) and 25 ms
  EXPECT_EQ(axis.stale_setpoints(), 1u);
  axis.advance_to(0.0351);  // 30 and 35 ms: 0.51 held
  EXPECT_EQ(axis.held_cycles(), held_before + 4);
}

TEST(AxisPlayout, AHorizonTripsTheAxisOnArrivalIfNotFiniteAndBeyondTheLimitWhenItWouldAct) {
  const ContourJob job = delayed_job();
  drive::AxisLimits limits;
  limits.command = 1.0;
  {
    AxisEndpoint axis(AxisEndpoint::simulated_drive(job, 0), job, 0, limits);
    axis.begin_iteration(1, 0.06);
    axis.submit_packet(0.0, 0, 0.005, {0.1, 0.2, std::numeric_limits<double>::quiet_NaN()});
    EXPECT_TRUE(axis.advance_to(0.010).empty());  // nothing of it plays
    ASSERT_TRUE(axis.fault().has_value());
    EXPECT_EQ(*axis.fault(), "command nan (cycle 0, horizon entry 2 of 3) not finite");
  }
  {
    AxisEndpoint axis(AxisEndpoint::simulated_drive(job, 0), job, 0, limits);
    axis.begin_iteration(1, 0.06);
    axis.submit_packet(0.0, 4, 0.005, {0.1, 1.5, 2.5});
    axis.submit_packet(0.005, 5, 0.010, {0.2, 0.3});  // arrives at 9 ms: 1.5 never acts
    axis.advance_to(0.0149);
    EXPECT_FALSE(axis.fault().has_value());
    EXPECT_DOUBLE_EQ(axis.supervised().input(), 0.2);
    const auto& tripped = axis.advance_to(0.030);  // 15 ms: 0.3; 20 ms: held; then 6 carries 1.2
    EXPECT_EQ(tripped.size(), 1u);
    axis.submit_packet(0.030, 6, 0.035, {1.2});
    axis.advance_to(0.040);
    ASSERT_TRUE(axis.fault().has_value());
    EXPECT_EQ(*axis.fault(), "command 1.2 (cycle 6, horizon entry 0 of 1) beyond the axis's limit 1");
    EXPECT_DOUBLE_EQ(axis.supervised().input(), 0.3);
  }
}

}  // namespace
}  // namespace netmc::sim

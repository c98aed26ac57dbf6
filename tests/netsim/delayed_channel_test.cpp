#include "netsim/delayed_channel.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "netsim/freshness_filter.hpp"
#include "netsim_test_support.hpp"

namespace netmc::netsim {
namespace {

using test::expect_invalid_argument;

constexpr double kPeriod = 0.001;

LinkModel make_link(std::unique_ptr<DelayModel> delay, std::unique_ptr<LossModel> loss = make_no_loss()) {
  return LinkModel(std::move(delay), std::move(loss), RandomStream(71));
}

std::vector<std::uint64_t> sequences_of(const std::vector<DelayedChannel<int>::Delivery>& deliveries) {
  std::vector<std::uint64_t> sequences;
  for (const auto& d : deliveries) sequences.push_back(d.sequence);
  return sequences;
}

TEST(DelayedChannel, DelayOfOneAndAHalfPeriodsArrivesTwoCyclesLater) {
  DelayedChannel<int> channel(make_link(make_constant_delay(1.5 * kPeriod)));
  for (int k = 0; k < 10; ++k) {
    const double now = k * kPeriod;
    const auto arrived = channel.receive_until(now);
    if (k < 2) {
      EXPECT_TRUE(arrived.empty()) << "cycle " << k;
    } else {
      // Sent at cycle k-2, arrived at (k-0.5) h: in the window (t_{k-1}, t_k].
      ASSERT_EQ(arrived.size(), 1u) << "cycle " << k;
      EXPECT_EQ(arrived[0].sequence, static_cast<std::uint64_t>(k - 2));
      EXPECT_EQ(arrived[0].payload, 100 * (k - 2));
      EXPECT_DOUBLE_EQ(arrived[0].send_time_s, (k - 2) * kPeriod);
      EXPECT_DOUBLE_EQ(arrived[0].arrival_time_s, (k - 0.5) * kPeriod);
    }
    EXPECT_TRUE(channel.send(now, static_cast<std::uint64_t>(k), 100 * k));
    EXPECT_EQ(channel.in_flight(), 2u - (k == 0 ? 1u : 0u));
  }
  EXPECT_EQ(channel.counters().sent, 10u);
  EXPECT_EQ(channel.counters().delivered, 8u);
  EXPECT_EQ(channel.counters().lost, 0u);
}

TEST(DelayedChannel, SeveralOrNoArrivalsPerWindow) {
  // Delays 2.5 h, 0.2 h, 0.3 h: nothing arrives in the first window, three in the third.
  DelayedChannel<int> channel(make_link(make_trace_delay({2.5 * kPeriod, 0.2 * kPeriod, 0.3 * kPeriod})));
  channel.send(0.0, 1, 0);
  channel.send(0.0, 2, 0);
  EXPECT_EQ(sequences_of(channel.receive_until(kPeriod)), (std::vector<std::uint64_t>{2}));
  channel.send(2.0 * kPeriod, 3, 0);  // arrives 2.3 h
  channel.send(2.0 * kPeriod, 4, 0);  // arrives 4.5 h
  EXPECT_TRUE(channel.receive_until(2.0 * kPeriod).empty());
  EXPECT_EQ(sequences_of(channel.receive_until(3.0 * kPeriod)), (std::vector<std::uint64_t>{3, 1}));
  EXPECT_EQ(channel.in_flight(), 1u);
}

TEST(DelayedChannel, ArrivalExactlyAtReceiveTimeIsIncluded) {
  // Binary-exact times so the comparison is exact.
  DelayedChannel<int> channel(make_link(make_constant_delay(0.5)));
  channel.send(0.25, 1, 7);
  EXPECT_TRUE(channel.receive_until(0.7499).empty());
  EXPECT_EQ(sequences_of(channel.receive_until(0.75)), (std::vector<std::uint64_t>{1}));
}

TEST(DelayedChannel, ReorderedArrivalsAndFreshnessFilterDropsStale) {
  DelayedChannel<int> channel(make_link(make_trace_delay({0.003, 0.001})));
  EXPECT_TRUE(channel.send(0.0, 1, 10));     // arrives at 3 ms
  EXPECT_TRUE(channel.send(0.001, 2, 20));   // arrives at 2 ms: overtakes seq 1
  const auto arrived = channel.receive_until(0.005);
  ASSERT_EQ(arrived.size(), 2u);
  EXPECT_EQ(arrived[0].sequence, 2u);
  EXPECT_DOUBLE_EQ(arrived[0].arrival_time_s, 0.002);
  EXPECT_EQ(arrived[1].sequence, 1u);
  EXPECT_DOUBLE_EQ(arrived[1].arrival_time_s, 0.003);

  FreshnessFilter filter;
  std::vector<int> applied;
  for (const auto& delivery : arrived) {
    if (filter.accept(delivery.sequence)) applied.push_back(delivery.payload);
  }
  EXPECT_EQ(applied, (std::vector<int>{20}));
  EXPECT_EQ(filter.stale_dropped(), 1u);
  EXPECT_EQ(filter.last_accepted(), 2u);
}

TEST(DelayedChannel, EqualArrivalTimesAreOrderedBySequence) {
  DelayedChannel<int> channel(make_link(make_trace_delay({0.5, 0.25})));
  channel.send(0.0, 9, 0);   // arrives 0.5
  channel.send(0.25, 4, 0);  // arrives 0.5 too, lower sequence
  EXPECT_EQ(sequences_of(channel.receive_until(1.0)), (std::vector<std::uint64_t>{4, 9}));
}

TEST(DelayedChannel, CountsLossesAndDeliveries) {
  DelayedChannel<int> channel(make_link(make_uniform_delay(0.0005, 0.004), make_bernoulli_loss(0.25)));
  std::uint64_t accepted = 0;
  for (int k = 0; k < 2000; ++k) accepted += channel.send(k * kPeriod, static_cast<std::uint64_t>(k), k) ? 1 : 0;
  const auto& counters = channel.counters();
  EXPECT_EQ(counters.sent, 2000u);
  EXPECT_EQ(counters.lost, 2000u - accepted);
  EXPECT_GT(counters.lost, 400u);  // about 500 expected
  EXPECT_LT(counters.lost, 600u);
  EXPECT_EQ(channel.in_flight() + counters.delivered, accepted);
  const auto drained = channel.receive_until(std::numeric_limits<double>::infinity());
  EXPECT_EQ(drained.size(), accepted);
  EXPECT_EQ(counters.delivered, accepted);
  EXPECT_EQ(channel.in_flight(), 0u);
  for (std::size_t i = 1; i < drained.size(); ++i) {
    EXPECT_LE(drained[i - 1].arrival_time_s, drained[i].arrival_time_s);
  }
}

TEST(DelayedChannel, AllLostWhenLossIsCertain) {
  DelayedChannel<int> channel(make_link(make_constant_delay(0.001), make_bernoulli_loss(1.0)));
  for (int k = 0; k < 10; ++k) EXPECT_FALSE(channel.send(k * kPeriod, static_cast<std::uint64_t>(k), k));
  EXPECT_EQ(channel.counters().lost, 10u);
  EXPECT_EQ(channel.in_flight(), 0u);
  EXPECT_FALSE(channel.next_arrival_s().has_value());
}

TEST(DelayedChannel, NextArrivalIsEarliestPending) {
  DelayedChannel<int> channel(make_link(make_trace_delay({0.004, 0.001, 0.002})));
  EXPECT_FALSE(channel.next_arrival_s().has_value());
  channel.send(0.0, 1, 0);  // 4 ms
  EXPECT_DOUBLE_EQ(*channel.next_arrival_s(), 0.004);
  channel.send(0.0, 2, 0);  // 1 ms
  channel.send(0.0, 3, 0);  // 2 ms
  EXPECT_DOUBLE_EQ(*channel.next_arrival_s(), 0.001);
  channel.receive_until(0.0015);
  EXPECT_DOUBLE_EQ(*channel.next_arrival_s(), 0.002);
  channel.receive_until(0.01);
  EXPECT_FALSE(channel.next_arrival_s().has_value());
}

TEST(DelayedChannel, ResetDropsInFlightAndReplays) {
  DelayedChannel<std::string> channel(make_link(make_uniform_delay(0.001, 0.003), make_bernoulli_loss(0.3)));
  std::vector<bool> first;
  for (int k = 0; k < 50; ++k) first.push_back(channel.send(k * kPeriod, static_cast<std::uint64_t>(k), "m"));
  const auto first_arrivals = channel.receive_until(1.0);
  channel.send(2.0, 99, "pending");
  channel.reset(RandomStream(71));
  EXPECT_EQ(channel.in_flight(), 0u);
  EXPECT_EQ(channel.counters().sent, 0u);
  std::vector<bool> second;
  for (int k = 0; k < 50; ++k) second.push_back(channel.send(k * kPeriod, static_cast<std::uint64_t>(k), "m"));
  EXPECT_EQ(second, first);
  const auto second_arrivals = channel.receive_until(1.0);
  ASSERT_EQ(second_arrivals.size(), first_arrivals.size());
  for (std::size_t i = 0; i < first_arrivals.size(); ++i) {
    EXPECT_EQ(second_arrivals[i].arrival_time_s, first_arrivals[i].arrival_time_s);
  }
}

TEST(DelayedChannel, RejectsNonFiniteTimes) {
  DelayedChannel<int> channel(make_link(make_no_delay()));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid_argument([&] { channel.send(nan, 1, 0); }, {"delayed channel", "send_time_s", "nan"});
  expect_invalid_argument([&] { channel.receive_until(nan); }, {"delayed channel", "time_s"});
  EXPECT_EQ(channel.counters().sent, 0u);
}

}  // namespace
}  // namespace netmc::netsim

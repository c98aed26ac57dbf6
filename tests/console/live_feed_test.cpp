// The live feed between a job's control loop and the console: bounded, newest kept, losses
// counted, never waiting; and the decimation that keeps the browser's share small.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "server/console/live_feed.hpp"

namespace netmc::console {
namespace {

sim::LiveCycle cycle(std::uint64_t k) {
  sim::LiveCycle c;
  c.cycle = k;
  c.time_s = static_cast<double>(k) * 1e-3;
  c.reference_m = control::AxisVector::Zero(2);
  c.position_m = control::AxisVector::Zero(2);
  c.command = control::AxisVector::Zero(2);
  return c;
}

TEST(LiveFeed, GivesTheCyclesSinceTheLastTakeInOrder) {
  LiveFeed feed;
  for (std::uint64_t k = 0; k < 10; ++k) feed.on_cycle(cycle(k));
  auto taken = feed.take();
  ASSERT_EQ(taken.cycles.size(), 10u);
  for (std::uint64_t k = 0; k < 10; ++k) EXPECT_EQ(taken.cycles[k].cycle, k);
  EXPECT_EQ(taken.dropped, 0u);
  EXPECT_TRUE(feed.take().cycles.empty());
}

TEST(LiveFeed, KeepsTheNewestAndCountsWhatItDropped) {
  LiveFeed feed;
  const std::uint64_t total = LiveFeed::kCapacity + 1000;
  for (std::uint64_t k = 0; k < total; ++k) feed.on_cycle(cycle(k));
  const auto taken = feed.take();
  ASSERT_EQ(taken.cycles.size(), LiveFeed::kCapacity);
  EXPECT_EQ(taken.cycles.front().cycle, 1000u);
  EXPECT_EQ(taken.cycles.back().cycle, total - 1);
  EXPECT_EQ(taken.dropped, 1000u);
  EXPECT_EQ(feed.take().dropped, 0u);  // counted once
}

TEST(LiveFeed, ALoopNeverWaitsForAReaderThatHoldsTheFeed) {
  // A reader that takes continuously: every cycle handed over is either taken or counted.
  LiveFeed feed;
  std::atomic<bool> done{false};
  std::uint64_t seen = 0, dropped = 0;
  std::thread reader([&] {
    while (!done.load()) {
      const auto taken = feed.take();
      seen += taken.cycles.size();
      dropped += taken.dropped;
    }
  });
  const std::uint64_t total = 200'000;
  for (std::uint64_t k = 0; k < total; ++k) feed.on_cycle(cycle(k));
  done.store(true);
  reader.join();
  const auto rest = feed.take();
  EXPECT_EQ(seen + rest.cycles.size() + dropped + rest.dropped, total);
}

TEST(Decimate, KeepsAtMostTheLimitEvenlyWithTheNewestLast) {
  std::vector<sim::LiveCycle> cycles;
  for (std::uint64_t k = 0; k < 1000; ++k) cycles.push_back(cycle(k));
  const auto kept = decimate(cycles, 50);
  ASSERT_EQ(kept.size(), 50u);
  EXPECT_EQ(kept.back().cycle, 999u);
  for (std::size_t i = 1; i < kept.size(); ++i) EXPECT_EQ(kept[i].cycle - kept[i - 1].cycle, 20u);
  EXPECT_EQ(decimate(cycles, 2000).size(), 1000u);  // under the limit: all
  const auto odd = decimate(std::vector<sim::LiveCycle>(cycles.begin(), cycles.begin() + 101), 50);
  EXPECT_LE(odd.size(), 50u);
  EXPECT_EQ(odd.back().cycle, 100u);
}

}  // namespace
}  // namespace netmc::console

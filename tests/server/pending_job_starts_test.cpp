// A job's start that waits for its server beside the node's loop (PendingJobStarts).

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "server/axis/pending_job_starts.hpp"

namespace netmc::axis {
namespace {

using Clock = PendingJobStarts::Clock;

netmc::dds::JobControl control(const std::string& axis, std::uint64_t job, netmc::dds::ControlKind kind) {
  netmc::dds::JobControl c;
  c.axis(axis);
  c.server("server-" + std::to_string(job));
  c.job_id(job);
  c.kind(kind);
  return c;
}

TEST(PendingJobStarts, AStartSettlesOnceItsServerReadsAndItsAxisLaterControlFollowsInOrder) {
  PendingJobStarts starts;
  const auto t0 = Clock::now();
  starts.wait(control("x", 1, netmc::dds::CONTROL_BEGIN_ITERATION), t0);
  EXPECT_TRUE(starts.waiting("x"));
  EXPECT_FALSE(starts.waiting("y"));  // the node's other axes go on
  starts.hold_back(control("x", 1, netmc::dds::CONTROL_END_ITERATION));
  starts.hold_back(control("x", 1, netmc::dds::CONTROL_END_JOB));
  bool linked = false;
  const auto is_linked = [&](const netmc::dds::JobControl&) { return linked; };
  EXPECT_TRUE(starts.settle(is_linked, t0 + std::chrono::seconds(1)).empty());
  linked = true;
  const auto settled = starts.settle(is_linked, t0 + std::chrono::seconds(1));
  ASSERT_EQ(settled.size(), 1u);
  EXPECT_TRUE(settled[0].linked);
  EXPECT_EQ(settled[0].begin.job_id(), 1u);
  ASSERT_EQ(settled[0].held_back.size(), 2u);
  EXPECT_EQ(settled[0].held_back[0].kind(), netmc::dds::CONTROL_END_ITERATION);
  EXPECT_EQ(settled[0].held_back[1].kind(), netmc::dds::CONTROL_END_JOB);
  EXPECT_TRUE(starts.empty());
}

TEST(PendingJobStarts, AStartWhoseServerNeverReadsIsGivenUpAfterFiveSeconds) {
  PendingJobStarts starts;
  const auto t0 = Clock::now();
  starts.wait(control("x", 7, netmc::dds::CONTROL_BEGIN_ITERATION), t0);
  const auto never = [](const netmc::dds::JobControl&) { return false; };
  EXPECT_TRUE(starts.settle(never, t0 + std::chrono::milliseconds(4999)).empty());
  const auto settled = starts.settle(never, t0 + std::chrono::milliseconds(5000));
  ASSERT_EQ(settled.size(), 1u);
  EXPECT_FALSE(settled[0].linked);
  EXPECT_EQ(settled[0].begin.job_id(), 7u);
  EXPECT_FALSE(starts.waiting("x"));
}

TEST(PendingJobStarts, HeldBackControlIsBoundedAndTheOldestGoFirst) {
  PendingJobStarts starts;
  const auto t0 = Clock::now();
  starts.wait(control("x", 1, netmc::dds::CONTROL_BEGIN_ITERATION), t0);
  const std::size_t sent = PendingJobStarts::kMaxHeldBack + 10;
  for (std::size_t i = 0; i < sent; ++i) starts.hold_back(control("x", 100 + i, netmc::dds::CONTROL_BEGIN_ITERATION));
  starts.hold_back(control("y", 1, netmc::dds::CONTROL_END_JOB));  // not waiting: not kept
  const auto settled = starts.settle([](const netmc::dds::JobControl&) { return true; }, t0);
  ASSERT_EQ(settled.size(), 1u);
  ASSERT_EQ(settled[0].held_back.size(), PendingJobStarts::kMaxHeldBack);
  EXPECT_EQ(settled[0].held_back.front().job_id(), 100u + 10u);
  EXPECT_EQ(settled[0].held_back.back().job_id(), 100u + sent - 1);
}

// 33 begins with 4 MiB specs from a peer to one waiting axis (without the bound, a 4-axis node
// grew to 711 MiB): the waiting start and one held spec remain, and the rest of the held-back
// control keeps its order.
TEST(PendingJobStarts, HeldBackJobSpecsAreBoundedToOne) {
  PendingJobStarts starts;
  const auto t0 = Clock::now();
  const std::vector<std::uint8_t> spec(4u << 20, 0x2A);
  auto begin = control("x", 1, netmc::dds::CONTROL_BEGIN_ITERATION);
  begin.job_spec(spec);
  starts.wait(begin, t0);
  starts.hold_back(control("x", 1, netmc::dds::CONTROL_END_ITERATION));
  for (std::uint64_t job = 2; job <= 33; ++job) {
    auto forged = control("x", job, netmc::dds::CONTROL_BEGIN_ITERATION);
    forged.job_spec(spec);
    starts.hold_back(forged);
  }
  starts.hold_back(control("x", 1, netmc::dds::CONTROL_END_JOB));
  const auto settled = starts.settle([](const netmc::dds::JobControl&) { return true; }, t0);
  ASSERT_EQ(settled.size(), 1u);
  EXPECT_EQ(settled[0].begin.job_spec().size(), spec.size());
  std::size_t spec_bytes = 0;
  for (const auto& held : settled[0].held_back) spec_bytes += held.job_spec().size();
  EXPECT_EQ(spec_bytes, spec.size());
  ASSERT_EQ(settled[0].held_back.size(), 3u);
  EXPECT_EQ(settled[0].held_back[0].kind(), netmc::dds::CONTROL_END_ITERATION);
  EXPECT_EQ(settled[0].held_back[1].job_id(), 33u);  // the newest begin
  EXPECT_EQ(settled[0].held_back[2].kind(), netmc::dds::CONTROL_END_JOB);
}

}  // namespace
}  // namespace netmc::axis

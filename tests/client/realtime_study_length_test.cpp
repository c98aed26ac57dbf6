#include "client/realtime_study_length.hpp"

#include <gtest/gtest.h>

#include "client/study_plan.hpp"

namespace netmc::cli {
namespace {

std::vector<netmc::v1::JobSpec> on_clock(std::vector<netmc::v1::JobSpec> jobs, const std::string& clock) {
  for (auto& job : jobs) job.set_clock(clock);
  return jobs;
}

TEST(RealtimeStudyLength, TheDefaultStudyIsItsRunsTimesTwentyRevolutionsOfEightSeconds) {
  // Paper 001's experiment: one revolution in 8 s, 20 iterations, per controller run.
  const auto jobs = on_clock(make_preset("seed001").jobs, "realtime");
  const RealtimeStudyLength length = realtime_study_length(jobs);
  EXPECT_EQ(length.jobs, jobs.size());
  EXPECT_EQ(length.iterations, 20 * jobs.size());
  EXPECT_DOUBLE_EQ(length.motion_s, 8.0 * 20.0 * static_cast<double>(jobs.size()));
  const auto notice = realtime_study_notice(jobs);
  ASSERT_TRUE(notice.has_value());
  EXPECT_NE(notice->find("of motion at the least"), std::string::npos) << *notice;
  EXPECT_NE(notice->find("for a first try: --controller adrc --iterations 2"), std::string::npos) << *notice;
}

TEST(RealtimeStudyLength, LockstepJobsAreNotCountedAndShortStudiesGetNoHint) {
  EXPECT_FALSE(realtime_study_notice(on_clock(make_preset("seed001").jobs, "lockstep")).has_value());
  auto job = make_preset("seed001").jobs.front();
  job.set_clock("realtime");
  job.set_iterations(2);
  const auto notice = realtime_study_notice({job});
  ASSERT_TRUE(notice.has_value());
  EXPECT_EQ(*notice, "realtime: 1 job, 2 iterations, 16 s of motion at the least");
}

}  // namespace
}  // namespace netmc::cli

// Which queued jobs netmc-server starts: disjoint axes at once, busy axes wait, no overtaking of
// an earlier job that waits for a shared axis, and the running-job limit.
#include <gtest/gtest.h>

#include "server/service/job_admission.hpp"

namespace netmc::service {
namespace {

using Axes = std::vector<std::string>;

TEST(JobAdmission, JobsOnDisjointAxesStartTogether) {
  EXPECT_EQ(admissible_jobs({Axes{"x", "y"}, Axes{"u", "v"}}, {}, 0, 32), (std::vector<std::size_t>{0, 1}));
}

TEST(JobAdmission, AJobWaitsWhileOneOfItsAxesIsBusy) {
  EXPECT_TRUE(admissible_jobs({Axes{"x", "y"}}, {"y"}, 1, 32).empty());
  EXPECT_EQ(admissible_jobs({Axes{"x", "y"}}, {"u"}, 1, 32), (std::vector<std::size_t>{0}));
}

TEST(JobAdmission, TwoQueuedJobsSharingAnAxisStartOneAfterTheOther) {
  EXPECT_EQ(admissible_jobs({Axes{"x", "y"}, Axes{"y", "z"}}, {}, 0, 32), (std::vector<std::size_t>{0}));
}

TEST(JobAdmission, NoJobOvertakesAnEarlierOneWaitingForASharedAxis) {
  // Job 0 waits for busy x; job 1 wants y, which job 0 also wants: it waits too, or job 0 could
  // starve behind a stream of jobs on y. Job 2 shares nothing with either and starts.
  const auto start = admissible_jobs({Axes{"x", "y"}, Axes{"y"}, Axes{"u", "v"}}, {"x"}, 1, 32);
  EXPECT_EQ(start, (std::vector<std::size_t>{2}));
}

TEST(JobAdmission, TheRunningLimitHoldsBackFreeJobsInOrder) {
  const std::vector<Axes> queued{Axes{"a"}, Axes{"b"}, Axes{"c"}};
  EXPECT_EQ(admissible_jobs(queued, {}, 2, 3), (std::vector<std::size_t>{0}));
  EXPECT_TRUE(admissible_jobs(queued, {}, 3, 3).empty());
  EXPECT_EQ(admissible_jobs(queued, {}, 0, 3), (std::vector<std::size_t>{0, 1, 2}));
}

}  // namespace
}  // namespace netmc::service

// Which queued jobs netmc-server starts: disjoint axes at once, busy axes wait, no overtaking of
// an earlier job that waits for a shared axis, and the running-job limit.
#include <gtest/gtest.h>

#include "server/service/job_admission.hpp"

namespace netmc::service {
namespace {

using Axes = std::vector<std::string>;

TEST(JobAdmission, AWaitingJobNamesWhatItWaitsBehind) {
  const std::vector<JobAxes> running{{3, {"u", "v"}}, {5, {"x", "w"}}};
  EXPECT_EQ(waiting_for({"x", "y"}, running, {}, 32), "job 5 (axis x)");
  // A running job comes before a queued one; among queued ones the earliest sharing an axis.
  EXPECT_EQ(waiting_for({"y", "x"}, running, {{6, {"y"}}}, 32), "job 5 (axis x)");
  EXPECT_EQ(waiting_for({"y"}, running, {{6, {"z"}}, {7, {"y", "z"}}, {8, {"y"}}}, 32),
            "job 7, queued before it (axis y)");
  EXPECT_EQ(waiting_for({"p"}, running, {}, 2), "the running-job limit (2)");
  EXPECT_EQ(waiting_for({"p"}, running, {}, 32), "");
  // Consistent with admissible_jobs: the job it says may start is the one that starts.
  EXPECT_EQ(admissible_jobs({Axes{"p"}}, {"u", "v", "x", "w"}, 2, 32), (std::vector<std::size_t>{0}));
}

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

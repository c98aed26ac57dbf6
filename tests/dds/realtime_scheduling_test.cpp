// Hard-timing options of netmc-server and netmc-axis: the CPU list syntax, and what happens to a
// request the operating system refuses (the process runs on, and says what was not applied).
#include <gtest/gtest.h>

#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>
#include <stdexcept>
#include <thread>

#include "server/realtime/realtime_scheduling.hpp"

namespace netmc::realtime {
namespace {

TEST(CpuList, ReadsTasksetSyntax) {
  EXPECT_EQ(parse_cpu_list("1", "--cpus"), (std::vector<int>{1}));
  EXPECT_EQ(parse_cpu_list("0,2", "--cpus"), (std::vector<int>{0, 2}));
  EXPECT_EQ(parse_cpu_list("2-4,7", "--cpus"), (std::vector<int>{2, 3, 4, 7}));
}

TEST(CpuList, RejectsAnythingElseNamingTheFlag) {
  for (const char* bad : {"", "a", "1,", "-1", "3-1", "1-", "1024", "99999", "1;rm", "0x1"}) {
    try {
      parse_cpu_list(bad, "--cpus");
      ADD_FAILURE() << "'" << bad << "' was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_EQ(std::string(error.what()).rfind("--cpus: ", 0), 0u) << error.what();
    }
  }
}

TEST(Scheduling, NothingRequestedIsTheNormalScheduler) {
  const SchedulingOutcome outcome = apply_process_scheduling({});
  EXPECT_TRUE(outcome.applied.empty());
  EXPECT_TRUE(outcome.fallbacks.empty());
  EXPECT_EQ(outcome.describe(), "normal scheduling");
}

// In a child process, so the test runner keeps its own scheduling.
int in_child(const std::function<int()>& body) {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(body());
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100;
}

TEST(Scheduling, AffinityAppliesToTheProcess) {
  EXPECT_EQ(in_child([] {
              const SchedulingOutcome outcome = apply_process_scheduling({0, {0}, false, -1});
              cpu_set_t set;
              CPU_ZERO(&set);
              ::sched_getaffinity(0, sizeof(set), &set);
              return outcome.fallbacks.empty() && CPU_COUNT(&set) == 1 && CPU_ISSET(0, &set) ? 0 : 1;
            }),
            0);
}

TEST(Scheduling, ARefusedRequestFallsBackAndSaysSo) {
  // A CPU this machine does not have cannot be pinned to: the process goes on unpinned.
  EXPECT_EQ(in_child([] {
              const SchedulingOutcome outcome = apply_process_scheduling({0, {1023}, false, -1});
              const bool named = outcome.describe().find("NOT APPLIED: --cpus 1023") != std::string::npos;
              return outcome.applied.empty() && outcome.fallbacks.size() == 1 && named ? 0 : 1;
            }),
            0);
  // SCHED_FIFO refused: without privileges (RLIMIT_RTPRIO 0 and no CAP_SYS_NICE once the
  // effective user is not root) the normal scheduler stays.
  EXPECT_EQ(in_child([] {
              if (::geteuid() == 0 && ::setresuid(65534, 65534, 65534) != 0) return 2;
              const SchedulingOutcome outcome = apply_process_scheduling({50, {}, false, -1});
              if (!outcome.fallbacks.empty()) return ::sched_getscheduler(0) == SCHED_OTHER ? 0 : 1;
              return ::sched_getscheduler(0) == SCHED_FIFO ? 3 : 1;  // permitted after all
            }),
            0);
}

TEST(Scheduling, AServingThreadLeavesTheRealtimeScheduler) {
  // Under SCHED_FIFO (root here; without the privilege there is nothing to leave): the thread
  // that leaves runs, and makes threads, on the normal scheduler; the others keep SCHED_FIFO.
  EXPECT_EQ(in_child([] {
              if (!apply_process_scheduling({50, {}, false, -1}).fallbacks.empty()) return 0;
              int serving = -1, made_by_serving = -1, loop = -1;
              std::thread server_thread([&] {
                if (!leave_realtime_scheduling()) return;
                serving = ::sched_getscheduler(0);
                std::thread([&] { made_by_serving = ::sched_getscheduler(0); }).join();
              });
              server_thread.join();
              std::thread([&] { loop = ::sched_getscheduler(0); }).join();
              const bool kept = ::sched_getscheduler(0) == SCHED_FIFO && loop == SCHED_FIFO;
              return serving == SCHED_OTHER && made_by_serving == SCHED_OTHER && kept ? 0 : 1;
            }),
            0);
}

}  // namespace
}  // namespace netmc::realtime

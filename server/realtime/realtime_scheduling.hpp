#pragma once
// Hard-timing options of a process that closes loops on the wall clock (netmc-server,
// netmc-axis --clock realtime): the SCHED_FIFO real-time scheduler, CPU affinity and locked
// memory. They are applied to the whole process before its DDS participant exists, so Fast
// DDS's receive and event threads, which wake the control loop, inherit them; a thread that
// serves clients leaves SCHED_FIFO again (leave_realtime_scheduling). Where the
// operating system does not permit one (no CAP_SYS_NICE / RLIMIT_RTPRIO, a container without
// it, a CPU not in the cpuset, RLIMIT_MEMLOCK), the process says so once and runs on without it.

#include <string>
#include <vector>

namespace netmc::realtime {

struct RealtimeScheduling {
  int fifo_priority = 0;     // SCHED_FIFO priority 1..99; 0: the normal scheduler
  std::vector<int> cpus;     // CPUs the process may run on; empty: any
  bool lock_memory = false;  // mlockall(current and future): no page fault in a cycle
  // PM QoS limit on the CPUs' wake-up latency [us], held while the process runs; -1: none.
  // 0 keeps idle CPUs polling instead of halting: on a virtual machine (cpuidle haltpoll) a
  // halted vCPU takes tens of microseconds to wake, as much as a loop's whole network budget.
  int cpu_latency_us = -1;
};

// What apply_process_scheduling did: each option in effect, or why it fell back.
struct SchedulingOutcome {
  std::vector<std::string> applied;
  std::vector<std::string> fallbacks;
  std::string describe() const;  // one line for the log
};

// Parses a CPU list as taskset and cpusets write it: "1", "0,2", "2-3,6". Throws
// std::invalid_argument naming `field` for anything else (or a CPU above 1023).
std::vector<int> parse_cpu_list(const std::string& text, const std::string& field);

// Applies `options` to the calling thread, the memory lock and the CPU latency limit to the
// process (until it exits); threads created afterwards inherit the policy and affinity. Never
// throws for a refused option.
SchedulingOutcome apply_process_scheduling(const RealtimeScheduling& options);

// Returns the calling thread to the normal scheduler (its affinity stays): for a thread that
// serves people rather than cycles (management requests, the browser console), so that its work,
// however much a client asks of it, never holds a CPU against a loop thread of the same
// SCHED_FIFO priority. Threads it creates afterwards inherit the normal scheduler. Never throws;
// false if the operating system refused.
bool leave_realtime_scheduling();

// Names the calling thread (at most 15 characters are kept) as `ps -L`, `top -H` and debuggers
// show it: which of a process's threads misses or hogs is then visible with its scheduler class.
void name_this_thread(const std::string& name);

// A loop thread that sleeps to deadlines: the kernel may delay its wake-ups by the timer slack
// (50 us by default for normal threads), a quarter of a 5 kHz period. This sets it to 1 ns.
void tighten_timer_slack();

}  // namespace netmc::realtime

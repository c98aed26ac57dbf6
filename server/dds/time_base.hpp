#pragma once
// The clock a node schedules realtime jobs on. Each host keeps its own; nothing assumes two
// hosts' clocks agree: the server measures every node's offset (ClockOffsetEstimator) and
// sends each node its job's start time on that node's own clock.
// See docs/architecture.md, "One cycle through the code" (realtime).

#include <chrono>
#include <string>

namespace netmc::dds {

enum class TimeBase {
  monotonic,  // CLOCK_MONOTONIC: counts from this host's boot (or its time namespace)
  realtime,   // CLOCK_REALTIME: wall time, in step across hosts where NTP/chrony runs
  tai,        // CLOCK_TAI: wall time without leap seconds, in step where linuxptp runs
};

TimeBase parse_time_base(const std::string& name);
const char* time_base_name(TimeBase base);
// The clock's reading in seconds.
double time_base_now_s(TimeBase base);
// The time of `base` at a past system-clock instant (e.g. a DDS reception timestamp).
double time_base_at_s(TimeBase base, std::chrono::system_clock::time_point when);
// The steady-clock instant at which `base` reads `time_s` (for Asio steady timers and waits).
std::chrono::steady_clock::time_point steady_time_at(TimeBase base, double time_s);

}  // namespace netmc::dds

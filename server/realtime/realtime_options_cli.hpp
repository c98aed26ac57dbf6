#pragma once
// The hard-timing flags shared by netmc-server and netmc-axis.

#include <CLI/CLI.hpp>

#include "server/realtime/realtime_scheduling.hpp"

namespace netmc::realtime {

inline void add_realtime_options(CLI::App& app, RealtimeScheduling& options) {
  app.add_option("--rt-priority", options.fifo_priority,
                 "Run the whole process (DDS threads included) under SCHED_FIFO at this priority (1-99); "
                 "where not permitted, a warning and the normal scheduler")
      ->check(CLI::Range(1, 99));
  app.add_option_function<std::string>(
      "--cpus", [&options](const std::string& value) { options.cpus = parse_cpu_list(value, "--cpus"); },
      "Pin the process to these CPUs, e.g. 1 or 2-3 (taskset syntax)");
  app.add_flag("--lock-memory", options.lock_memory, "mlockall: keep every page in RAM (no page fault in a cycle)");
  app.add_option("--cpu-latency", options.cpu_latency_us,
                 "Hold the CPUs' wake-up latency at most this many microseconds while running (PM QoS, "
                 "/dev/cpu_dma_latency, root); 0: idle CPUs poll instead of halting, at the price of their idle time")
      ->check(CLI::Range(0, 1000000));
}

}  // namespace netmc::realtime

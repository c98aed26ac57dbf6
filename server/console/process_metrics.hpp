#pragma once
// The process's own numbers in Prometheus's standard names (process_cpu_seconds_total,
// process_resident_memory_bytes, ...), read from /proc/self as the Prometheus client libraries
// read them. Pure: std and POSIX only (tests/console).

#include <optional>
#include <string>

namespace netmc::console {

struct ProcessMetrics {
  double cpu_seconds = 0.0;         // user + system
  double resident_bytes = 0.0;
  double virtual_bytes = 0.0;
  double start_time_unix_s = 0.0;
  double open_fds = 0.0;
  double max_fds = 0.0;             // the soft limit
};

// nullopt when /proc cannot be read (another system).
std::optional<ProcessMetrics> read_process_metrics();

// The fields of a /proc/PID/stat line (after the command's parentheses, which may hold spaces),
// with the machine's clock ticks per second, page size and boot time (/proc/stat's btime).
// nullopt when the line is not of that form.
std::optional<ProcessMetrics> parse_proc_stat(const std::string& line, double ticks_per_s, double page_bytes,
                                              double boot_time_unix_s);

}  // namespace netmc::console

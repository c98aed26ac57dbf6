#include "server/console/process_metrics.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace netmc::console {

std::optional<ProcessMetrics> parse_proc_stat(const std::string& line, double ticks_per_s, double page_bytes,
                                              double boot_time_unix_s) {
  // pid (comm) state ppid ...: fields 3.. follow the last ')'.
  const auto close = line.rfind(')');
  if (close == std::string::npos || !(ticks_per_s > 0.0)) return std::nullopt;
  std::istringstream rest(line.substr(close + 1));
  std::vector<std::string> fields;  // fields[0] is field 3 (state)
  for (std::string field; rest >> field && fields.size() < 22;) fields.push_back(field);
  if (fields.size() < 22) return std::nullopt;
  const auto number = [&fields](std::size_t field) { return std::stod(fields[field - 3]); };
  try {
    ProcessMetrics m;
    m.cpu_seconds = (number(14) + number(15)) / ticks_per_s;  // utime + stime
    m.start_time_unix_s = boot_time_unix_s + number(22) / ticks_per_s;
    m.virtual_bytes = number(23);
    m.resident_bytes = number(24) * page_bytes;
    return m;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<ProcessMetrics> read_process_metrics() {
  std::ifstream stat_file("/proc/self/stat");
  std::string line;
  if (!std::getline(stat_file, line)) return std::nullopt;
  double boot_time = 0.0;
  std::ifstream machine("/proc/stat");
  for (std::string key; machine >> key;) {
    if (key == "btime") {
      machine >> boot_time;
      break;
    }
    machine.ignore(1 << 20, '\n');
  }
  auto metrics = parse_proc_stat(line, static_cast<double>(::sysconf(_SC_CLK_TCK)),
                                 static_cast<double>(::sysconf(_SC_PAGESIZE)), boot_time);
  if (!metrics) return std::nullopt;
  std::error_code error;
  double fds = 0.0;
  for (auto it = std::filesystem::directory_iterator("/proc/self/fd", error);
       !error && it != std::filesystem::directory_iterator(); it.increment(error)) {
    fds += 1.0;
  }
  metrics->open_fds = fds;
  rlimit limit{};
  if (::getrlimit(RLIMIT_NOFILE, &limit) == 0) metrics->max_fds = static_cast<double>(limit.rlim_cur);
  return metrics;
}

}  // namespace netmc::console

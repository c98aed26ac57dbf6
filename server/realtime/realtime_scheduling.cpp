#include "server/realtime/realtime_scheduling.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sched.h>
#include <sys/mman.h>
#include <fcntl.h>
#include <pthread.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace netmc::realtime {
namespace {

constexpr int kMaxCpu = 1023;

int parse_cpu(const std::string& text, const std::string& field) {
  if (text.empty() || text.size() > 4 || text.find_first_not_of("0123456789") != std::string::npos) {
    throw std::invalid_argument(field + ": expected CPU numbers like 1, 0,2 or 2-3, got '" + text.substr(0, 32) + "'");
  }
  const int cpu = std::stoi(text);
  if (cpu > kMaxCpu) throw std::invalid_argument(field + ": CPU " + text + " is above " + std::to_string(kMaxCpu));
  return cpu;
}

std::string error_text(int error) {
  const char* hint = error == EPERM ? " (needs root, CAP_SYS_NICE or an RLIMIT_RTPRIO of that priority)" : "";
  return fmt::format("{}{}", std::strerror(error), hint);
}

}  // namespace

std::string SchedulingOutcome::describe() const {
  std::string out = applied.empty() ? "normal scheduling" : fmt::format("{}", fmt::join(applied, ", "));
  for (const auto& item : fallbacks) out += fmt::format("; NOT APPLIED: {}", item);
  return out;
}

std::vector<int> parse_cpu_list(const std::string& text, const std::string& field) {
  std::vector<int> cpus;
  std::string item;
  for (const char c : text + ",") {
    if (c != ',') {
      item += c;
      continue;
    }
    if (const auto dash = item.find('-'); dash != std::string::npos) {
      const int first = parse_cpu(item.substr(0, dash), field);
      const int last = parse_cpu(item.substr(dash + 1), field);
      if (last < first) throw std::invalid_argument(field + ": range '" + item + "' runs backwards");
      for (int cpu = first; cpu <= last; ++cpu) cpus.push_back(cpu);
    } else {
      cpus.push_back(parse_cpu(item, field));
    }
    item.clear();
  }
  return cpus;
}

SchedulingOutcome apply_process_scheduling(const RealtimeScheduling& options) {
  SchedulingOutcome outcome;
  if (options.lock_memory) {
    if (::mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      outcome.applied.push_back("memory locked");
    } else {
      outcome.fallbacks.push_back("--lock-memory: mlockall: " + error_text(errno));
    }
  }
  if (!options.cpus.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    for (const int cpu : options.cpus) CPU_SET(cpu, &set);
    const std::string list = fmt::format("{}", fmt::join(options.cpus, ","));
    if (::sched_setaffinity(0, sizeof(set), &set) == 0) {
      outcome.applied.push_back("CPUs " + list);
    } else {
      outcome.fallbacks.push_back("--cpus " + list + ": sched_setaffinity: " + error_text(errno));
    }
  }
  if (options.cpu_latency_us >= 0) {
    // The limit holds while the file stays open: for the process's lifetime (it is never closed).
    const int fd = ::open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
    const std::int32_t value = options.cpu_latency_us;
    if (fd >= 0 && ::write(fd, &value, sizeof(value)) == static_cast<ssize_t>(sizeof(value))) {
      outcome.applied.push_back(fmt::format("CPU wake-up latency <= {} us", options.cpu_latency_us));
    } else {
      outcome.fallbacks.push_back(
          fmt::format("--cpu-latency {}: /dev/cpu_dma_latency: {}", options.cpu_latency_us, error_text(errno)));
      if (fd >= 0) ::close(fd);
    }
  }
  if (options.fifo_priority > 0) {
    sched_param param{};
    param.sched_priority = options.fifo_priority;
    if (::sched_setscheduler(0, SCHED_FIFO, &param) == 0) {
      outcome.applied.push_back(fmt::format("SCHED_FIFO priority {}", options.fifo_priority));
    } else {
      outcome.fallbacks.push_back(
          fmt::format("--rt-priority {}: sched_setscheduler: {}", options.fifo_priority, error_text(errno)));
    }
  }
  return outcome;
}

bool leave_realtime_scheduling() {
  const sched_param param{};
  return ::sched_setscheduler(0, SCHED_OTHER, &param) == 0;
}

void name_this_thread(const std::string& name) { ::pthread_setname_np(::pthread_self(), name.substr(0, 15).c_str()); }

void tighten_timer_slack() { ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL); }

}  // namespace netmc::realtime

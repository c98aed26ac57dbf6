#include "server/dds/time_base.hpp"

#include <time.h>

#include <stdexcept>

namespace netmc::dds {
namespace {

clockid_t clock_of(TimeBase base) {
  switch (base) {
    case TimeBase::monotonic: return CLOCK_MONOTONIC;
    case TimeBase::realtime: return CLOCK_REALTIME;
    case TimeBase::tai: return CLOCK_TAI;
  }
  return CLOCK_MONOTONIC;
}

double steady_now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

TimeBase parse_time_base(const std::string& name) {
  if (name == "monotonic") return TimeBase::monotonic;
  if (name == "realtime") return TimeBase::realtime;
  if (name == "tai") return TimeBase::tai;
  throw std::invalid_argument("--time-base: expected monotonic, realtime or tai, got '" + name + "'");
}

const char* time_base_name(TimeBase base) {
  switch (base) {
    case TimeBase::monotonic: return "monotonic";
    case TimeBase::realtime: return "realtime";
    case TimeBase::tai: return "tai";
  }
  return "monotonic";
}

double time_base_now_s(TimeBase base) {
  timespec now{};
  ::clock_gettime(clock_of(base), &now);
  return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

double time_base_at_s(TimeBase base, std::chrono::system_clock::time_point when) {
  const double ago_s = std::chrono::duration<double>(std::chrono::system_clock::now() - when).count();
  return time_base_now_s(base) - ago_s;
}

std::chrono::steady_clock::time_point steady_time_at(TimeBase base, double time_s) {
  // steady_clock is CLOCK_MONOTONIC on Linux; another base is mapped through the present
  // difference (a step of that clock during a job moves the remaining cycles with it).
  const double steady_s = base == TimeBase::monotonic ? time_s : time_s - time_base_now_s(base) + steady_now_s();
  return std::chrono::steady_clock::time_point(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(steady_s)));
}

}  // namespace netmc::dds

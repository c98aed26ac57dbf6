#include "server/axis/pending_job_starts.hpp"

#include <algorithm>

namespace netmc::axis {

void PendingJobStarts::wait(const netmc::dds::JobControl& begin, Clock::time_point now) {
  waiting_.emplace(begin.axis(), Waiting{begin, now + kLinkTimeout, {}});
}

void PendingJobStarts::hold_back(const netmc::dds::JobControl& control) {
  const auto it = waiting_.find(control.axis());
  if (it == waiting_.end()) return;
  auto& held = it->second.held_back;
  const auto has_spec = [](const netmc::dds::JobControl& c) { return !c.job_spec().empty(); };
  if (has_spec(control) &&
      static_cast<std::size_t>(std::count_if(held.begin(), held.end(), has_spec)) >= kMaxHeldBackSpecs) {
    held.erase(std::find_if(held.begin(), held.end(), has_spec));
  }
  if (held.size() >= kMaxHeldBack) held.erase(held.begin());
  held.push_back(control);
}

std::vector<PendingJobStarts::Settled> PendingJobStarts::settle(
    const std::function<bool(const netmc::dds::JobControl&)>& linked, Clock::time_point now) {
  std::vector<Settled> settled;
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    const bool is_linked = linked(it->second.begin);
    if (!is_linked && now < it->second.deadline) {
      ++it;
      continue;
    }
    settled.push_back({std::move(it->second.begin), is_linked, std::move(it->second.held_back)});
    it = waiting_.erase(it);
  }
  return settled;
}

}  // namespace netmc::axis

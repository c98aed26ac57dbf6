#include "server/axis/pending_job_starts.hpp"

namespace netmc::axis {

void PendingJobStarts::wait(const netmc::dds::JobControl& begin, Clock::time_point now) {
  waiting_.emplace(begin.axis(), Waiting{begin, now + kLinkTimeout, {}});
}

void PendingJobStarts::hold_back(const netmc::dds::JobControl& control) {
  const auto it = waiting_.find(control.axis());
  if (it == waiting_.end()) return;
  auto& held = it->second.held_back;
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

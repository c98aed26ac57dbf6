#include "server/axis/pending_job_starts.hpp"

namespace netmc::axis {

void PendingJobStarts::wait(const netmc::dds::JobControl& begin, Clock::time_point now) {
  waiting_.emplace(begin.axis(), Waiting{begin, now + kServerReadTimeout, {}});
}

void PendingJobStarts::hold_back(const netmc::dds::JobControl& control) {
  const auto it = waiting_.find(control.axis());
  if (it == waiting_.end()) return;
  auto& held = it->second.held_back;
  if (held.size() >= kMaxHeldBack) held.erase(held.begin());
  held.push_back(control);
}

std::vector<PendingJobStarts::Settled> PendingJobStarts::settle(
    const std::function<bool(const netmc::dds::JobControl&)>& server_reads, Clock::time_point now) {
  std::vector<Settled> settled;
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    const bool reads = server_reads(it->second.begin);
    if (!reads && now < it->second.deadline) {
      ++it;
      continue;
    }
    settled.push_back({std::move(it->second.begin), reads, std::move(it->second.held_back)});
    it = waiting_.erase(it);
  }
  return settled;
}

}  // namespace netmc::axis

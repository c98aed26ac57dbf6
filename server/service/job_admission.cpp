#include "server/service/job_admission.hpp"

#include <algorithm>

namespace netmc::service {

std::vector<std::size_t> admissible_jobs(const std::vector<std::vector<std::string>>& queued,
                                         const std::set<std::string>& busy_axes, std::size_t running,
                                         std::size_t max_running) {
  std::vector<std::size_t> start;
  std::set<std::string> claimed = busy_axes;  // busy, or wanted by an earlier job
  for (std::size_t i = 0; i < queued.size(); ++i) {
    const auto& axes = queued[i];
    const bool free =
        std::none_of(axes.begin(), axes.end(), [&](const std::string& axis) { return claimed.count(axis) > 0; });
    claimed.insert(axes.begin(), axes.end());
    if (free && running + start.size() < max_running) start.push_back(i);
  }
  return start;
}

}  // namespace netmc::service

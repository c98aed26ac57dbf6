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

std::string waiting_for(const std::vector<std::string>& axes, const std::vector<JobAxes>& running,
                        const std::vector<JobAxes>& queued_before, std::size_t max_running) {
  const auto shared = [&](const JobAxes& other) -> std::string {
    for (const auto& axis : axes) {
      if (std::find(other.axes.begin(), other.axes.end(), axis) != other.axes.end()) return axis;
    }
    return "";
  };
  for (const auto& job : running) {
    if (const auto axis = shared(job); !axis.empty()) return "job " + std::to_string(job.id) + " (axis " + axis + ")";
  }
  for (const auto& job : queued_before) {
    if (const auto axis = shared(job); !axis.empty()) {
      return "job " + std::to_string(job.id) + ", queued before it (axis " + axis + ")";
    }
  }
  if (running.size() >= max_running) return "the running-job limit (" + std::to_string(max_running) + ")";
  return "";
}

}  // namespace netmc::service

#include "server/store/job_list.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace netmc::store {

JobFilter job_filter(const netmc::v1::ListJobs& request) {
  JobFilter filter;
  filter.state = request.state();
  filter.label_contains = request.label_contains();
  filter.since_unix_s = request.since_unix_s();
  filter.limit = request.limit() == 0 ? 50 : std::min<std::uint32_t>(request.limit(), 10000);
  static const std::set<std::string> states{"", "queued", "running", "done", "failed", "cancelled"};
  if (!states.contains(filter.state)) {
    throw std::invalid_argument("state: '" + filter.state.substr(0, 32) +
                                "' is none of queued, running, done, failed, cancelled");
  }
  if (!std::isfinite(filter.since_unix_s)) throw std::invalid_argument("since: not a finite time");
  if (filter.label_contains.size() > 256) throw std::invalid_argument("label: longer than 256 characters");
  return filter;
}

netmc::v1::JobList job_list(const std::vector<StoredJob>& jobs, bool persistent) {
  netmc::v1::JobList list;
  list.set_persistent(persistent);
  for (const auto& job : jobs) {
    auto& record = *list.add_jobs();
    record.set_job_id(job.id);
    record.set_label(job.label);
    record.set_state(job.state);
    record.set_error(job.error);
    record.set_owner(job.owner);
    record.set_accepted_unix_s(job.accepted_unix_s);
    record.set_ended_unix_s(job.ended_unix_s);
    record.set_iterations_done(job.iterations_done);
    record.set_iterations_total(job.iterations_total);
  }
  return list;
}

}  // namespace netmc::store

#pragma once
// Which queued jobs may start now (netmc-server runs jobs on disjoint axes at once). In
// submission order, a job starts when none of its axes is busy or wanted by an earlier job that
// still waits, and fewer than `max_running` jobs run: a job never overtakes an earlier one that
// waits for one of its axes, and a job whose axes are free never waits behind one that does not
// share them.

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace netmc::service {

// Indices into `queued` (each job's axes, in submission order) of the jobs to start, ascending.
std::vector<std::size_t> admissible_jobs(const std::vector<std::vector<std::string>>& queued,
                                         const std::set<std::string>& busy_axes, std::size_t running,
                                         std::size_t max_running);

// A job of the server, as waiting_for sees it.
struct JobAxes {
  std::uint64_t id = 0;
  std::vector<std::string> axes;
};

// Why the queued job `axes` has not started: the first running job, then the first job queued
// before it, that shares an axis ("job 3 (axis x)", "job 4, queued before it (axis y)"), else the
// running-job limit; empty if nothing holds it back.
std::string waiting_for(const std::vector<std::string>& axes, const std::vector<JobAxes>& running,
                        const std::vector<JobAxes>& queued_before, std::size_t max_running);

}  // namespace netmc::service
